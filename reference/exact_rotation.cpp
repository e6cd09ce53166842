#include "exact_rotation.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <random>

namespace corofem::reference {

Eigen::Quaterniond rotation_factor_horn(const Eigen::Matrix3d& m) {
  // f(q) = tr(Rt(q)^T M) with Rt(q) v = q v q* (a quadratic form in q, = R(q) |q|^2).
  auto f = [&](const Eigen::Vector4d& c) {
    const Eigen::Quaterniond q(c[0], c[1], c[2], c[3]);
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Quaterniond e(0, k == 0, k == 1, k == 2);
      const Eigen::Vector3d column = (q * e * q.conjugate()).vec();  // Rt(q) e_k
      sum += column.dot(m.col(k));
    }
    return sum;
  };
  Eigen::Matrix4d n;
  for (int i = 0; i < 4; ++i) n(i, i) = f(Eigen::Vector4d::Unit(i));
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      n(i, j) = n(j, i) =
          0.5 * (f(Eigen::Vector4d::Unit(i) + Eigen::Vector4d::Unit(j)) - n(i, i) - n(j, j));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(n);
  const Eigen::Vector4d top = eig.eigenvectors().col(3);
  return Eigen::Quaterniond(top[0], top[1], top[2], top[3]).normalized();
}

Eigen::Matrix3d rotation_factor_svd(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d signs(1, 1, (svd.matrixU() * svd.matrixV().transpose()).determinant());
  return svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
}

Eigen::Matrix3d brute_force_minimize(const std::function<double(const Eigen::Matrix3d&)>& energy,
                                     int samples, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double two_pi = 2 * EIGEN_PI;
  Eigen::Matrix3d best = Eigen::Matrix3d::Identity();
  double best_energy = energy(best);
  for (int s = 0; s < samples; ++s) {
    const double u1 = u(rng), u2 = u(rng), u3 = u(rng);
    const Eigen::Quaterniond q(
        std::sqrt(u1) * std::cos(two_pi * u3), std::sqrt(1 - u1) * std::sin(two_pi * u2),
        std::sqrt(1 - u1) * std::cos(two_pi * u2), std::sqrt(u1) * std::sin(two_pi * u3));
    const Eigen::Matrix3d r = q.toRotationMatrix();
    const double e = energy(r);
    if (e < best_energy) {
      best_energy = e;
      best = r;
    }
  }
  for (double step = 0.1; step > 1e-11;) {
    bool improved = false;
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {-1.0, 1.0}) {
        const Eigen::Matrix3d r =
            Eigen::AngleAxisd(sign * step, Eigen::Vector3d::Unit(axis)).toRotationMatrix() * best;
        const double e = energy(r);
        if (e < best_energy) {
          best_energy = e;
          best = r;
          improved = true;
        }
      }
    if (!improved) step *= 0.5;
  }
  return best;
}

}  // namespace corofem::reference
