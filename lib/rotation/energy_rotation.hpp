#pragma once
// The paper's rotation extraction by energy minimization (Section 3, eqs. 3-8) and its exact
// closed-form minimizer. With S = sum_g w z_g y_g^T (= F C, quadrature of eq. 3), the energy is
// E(q) = a |q|^4 - 2 q^T N q + c, q the quaternion of Q^T (the paper's variable), a = sum w |z|^2,
// N = horn_matrix(S^T); its minimizer over unit q is N's top eigenvector (Horn 1987).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "rotation/element_quadrature.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// 4x4 symmetric N with q^T N q = tr(R(q)^T M) for unit quaternions q = (w, x, y, z).
Eigen::Matrix4d horn_matrix(const Mat3& m);

/// Moment arms of every element (element_quadrature.hpp) from its rest quadrature.
std::vector<MomentArms> rest_moment_arms(const TetMesh& mesh);

/// Quadrature of the deformed element: S = sum_g w z_g y_g^T = sum_v p_v h_v^T and
/// a = sum_g w |z_g|^2, z_g the deformed offsets from the deformed centroid at the quadrature
/// points.
Mat3 deformed_moment(const MomentArms& rest, const Tet& tet, const std::vector<Vec3>& positions,
                     double& a);

/// Outcome of one element's Newton solve.
struct NewtonOutcome {
  Mat3 rotation;
  int iterations = 0;
  bool fell_back =
      false;  ///< singular or indefinite Hessian, or no convergence: exact minimizer used
};

/// The quaternion (w, x, y, z) of a rotation matrix m (row-major), up to sign: the row of
/// 4 q q^T (its entries are sums and differences of m's) with the largest diagonal entry 4 q_k^2,
/// divided by 2 |2 q_k| (Shepperd 1978). Branch-free (the row is chosen by selects), so that it
/// also runs on the batched Newton's lanes: T is double, or a vector of lanes (whose comparisons
/// give masks) with its own square root `root`; the largest diagonal keeps the division well
/// conditioned.
template <class T, class Root>
inline void quaternion_of_rotation(const T (&m)[9], T (&q)[4], const Root& root) {
  const T t[4] = {1 + m[0] + m[4] + m[8], 1 + m[0] - m[4] - m[8], 1 - m[0] + m[4] - m[8],
                  1 - m[0] - m[4] + m[8]};
  const T wx = m[7] - m[5], wy = m[2] - m[6], wz = m[3] - m[1];
  const T xy = m[1] + m[3], xz = m[2] + m[6], yz = m[5] + m[7];
  const auto x_over_w = t[1] > t[0];
  T best = x_over_w ? t[1] : t[0];
  T r0 = x_over_w ? wx : t[0], r1 = x_over_w ? t[1] : wx, r2 = x_over_w ? xy : wy,
    r3 = x_over_w ? xz : wz;
  const auto y_best = t[2] > best;
  best = y_best ? t[2] : best;
  r0 = y_best ? wy : r0;
  r1 = y_best ? xy : r1;
  r2 = y_best ? t[2] : r2;
  r3 = y_best ? yz : r3;
  const auto z_best = t[3] > best;
  best = z_best ? t[3] : best;
  r0 = z_best ? wz : r0;
  r1 = z_best ? xz : r1;
  r2 = z_best ? yz : r2;
  r3 = z_best ? t[3] : r3;
  const T scale = 0.5 / root(best);
  q[0] = r0 * scale;
  q[1] = r1 * scale;
  q[2] = r2 * scale;
  q[3] = r3 * scale;
}
inline void quaternion_of_rotation(const double (&m)[9], double (&q)[4]) {
  quaternion_of_rotation(m, q, [](double x) { return std::sqrt(x); });
}

/// The rotation matrix (row-major) of q / |q|, q (w, x, y, z) not necessarily of unit length:
/// the rotation matrix of a unit quaternion with 2 replaced by 2 / |q|^2 (no square root). T as
/// for quaternion_of_rotation.
template <class T>
inline void rotation_of_quaternion(const T (&q)[4], T (&m)[9]) {
  const T s = 2 / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const T xx = s * q[1] * q[1], yy = s * q[2] * q[2], zz = s * q[3] * q[3];
  const T xy = s * q[1] * q[2], xz = s * q[1] * q[3], yz = s * q[2] * q[3];
  const T wx = s * q[0] * q[1], wy = s * q[0] * q[2], wz = s * q[0] * q[3];
  m[0] = 1 - (yy + zz);
  m[1] = xy - wz;
  m[2] = xz + wy;
  m[3] = xy + wz;
  m[4] = 1 - (xx + zz);
  m[5] = yz - wx;
  m[6] = xz - wy;
  m[7] = yz + wx;
  m[8] = 1 - (xx + yy);
}

/// The paper's q describes Q^T: Newton starts from the quaternion of the warm rotation's
/// transpose, and its q gives back Q = R(q / |q|)^T.
inline Eigen::Vector4d newton_start(const Mat3& warm) {
  const double m[9] = {warm(0, 0), warm(1, 0), warm(2, 0), warm(0, 1), warm(1, 1),
                       warm(2, 1), warm(0, 2), warm(1, 2), warm(2, 2)};  // warm^T, row-major
  double q[4];
  quaternion_of_rotation(m, q);
  return {q[0], q[1], q[2], q[3]};
}
inline Mat3 newton_rotation(const Eigen::Vector4d& q) {
  const double v[4] = {q[0], q[1], q[2], q[3]};
  double m[9];
  rotation_of_quaternion(v, m);  // R(q), row-major: read as column-major it is R^T = Q
  return Eigen::Map<const Mat3>(m);
}

/// Newton on (q, lambda) for eqs. (5)-(8): gradient 4a|q|^2 q - 4Nq + 2 lambda q, Hessian
/// 4a(|q|^2 I + 2 q q^T) - 4N + 2 lambda I, bordered by 2q (eq. 8). Starts from `warm` (Q of the
/// previous step), lambda from stationarity at the start. Converged when
/// |grad_q| / (4a) + |q.q - 1| < tolerance. At a unique minimizer the Hessian is positive
/// definite (8a q q^T + 4(mu_max I - N)); it is singular exactly where the minimizer is not unique,
/// and such elements, like ones where Newton ends at a saddle, fall back to the exact minimizer.
NewtonOutcome energy_newton_rotation(const Mat3& s, double a, const Mat3& warm, double tolerance,
                                     int max_iterations);

/// Proper rotation factor of S (the exact minimizer): Higham polar of S when det S is safely
/// positive, else the SVD route with the sign fix.
Mat3 energy_exact_rotation(const Mat3& s);

class EnergyNewtonExtractor : public RotationExtractor {
 public:
  /// `params`: newton_tolerance, newton_max_iterations (energy_newton_traits declares them).
  EnergyNewtonExtractor(const TetMesh& mesh, const Parameters& params);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  double tolerance_;
  int max_iterations_;
  std::vector<MomentArms> rest_;
};

class EnergyExactExtractor : public RotationExtractor {
 public:
  explicit EnergyExactExtractor(const TetMesh& mesh);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  std::vector<MomentArms> rest_;
};

/// The registration of these methods (rotation/rotation_method.hpp).
RotationMethodTraits energy_newton_traits();
RotationMethodTraits energy_exact_traits();

}  // namespace corofem
