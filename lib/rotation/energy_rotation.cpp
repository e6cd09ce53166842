#include "rotation/energy_rotation.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/threads.hpp"
#include "rotation/energy_newton_batch.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/rotation_factor.hpp"

namespace corofem {

Eigen::Matrix4d horn_matrix(const Mat3& m) {
  // Coefficients of tr(R(q)^T M) = sum_ij R_ij(q) M_ij, R(q) the rotation matrix of unit q.
  Eigen::Matrix4d n;
  n(0, 0) = m(0, 0) + m(1, 1) + m(2, 2);
  n(1, 1) = m(0, 0) - m(1, 1) - m(2, 2);
  n(2, 2) = -m(0, 0) + m(1, 1) - m(2, 2);
  n(3, 3) = -m(0, 0) - m(1, 1) + m(2, 2);
  n(0, 1) = n(1, 0) = m(2, 1) - m(1, 2);
  n(0, 2) = n(2, 0) = m(0, 2) - m(2, 0);
  n(0, 3) = n(3, 0) = m(1, 0) - m(0, 1);
  n(1, 2) = n(2, 1) = m(0, 1) + m(1, 0);
  n(1, 3) = n(3, 1) = m(0, 2) + m(2, 0);
  n(2, 3) = n(3, 2) = m(1, 2) + m(2, 1);
  return n;
}

std::vector<MomentArms> rest_moment_arms(const TetMesh& mesh) {
  std::vector<MomentArms> rest;
  rest.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets) {
    const std::array<Vec3, 4> v{mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]};
    rest.push_back(moment_arms(quadrature_points(v, signed_volume(v[0], v[1], v[2], v[3]))));
  }
  return rest;
}

Mat3 deformed_moment(const MomentArms& rest, const Tet& tet, const std::vector<Vec3>& positions,
                     double& a) {
  const Vec3 p[4] = {positions[tet[0]], positions[tet[1]], positions[tet[2]], positions[tet[3]]};
  const Vec3 mean = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  Mat3 s = Mat3::Zero();
  double spread = 0;
  for (int v = 0; v < 4; ++v) {
    const Vec3 z =
        p[v] - mean;  // sum_v h_v = 0: the mean drops out of S, and z keeps it well scaled
    s.noalias() += z * rest.h[v].transpose();
    spread += z.squaredNorm();
  }
  a = rest.c * spread;
  return s;
}

namespace {

/// Cholesky factor of a 4x4 symmetric matrix, unrolled. Eigen's LLT is its general blocked code
/// with an L1 norm on top: replacing it took BM_Rotation/energy_newton_warm from 200 to 127 ns
/// per element (2 threads, same session). `ok` is false where a pivot is not positive, as LLT's
/// info().
struct Cholesky4 {
  double l[4][4] = {};
  double inverse_diagonal[4] = {};
  bool ok = true;

  explicit Cholesky4(const Eigen::Matrix4d& h) {
    for (int j = 0; j < 4; ++j) {
      double d = h(j, j);
      for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
      if (!(d > 0)) {
        ok = false;
        return;
      }
      const double ljj = std::sqrt(d);
      l[j][j] = ljj;
      inverse_diagonal[j] = 1 / ljj;
      for (int i = j + 1; i < 4; ++i) {
        double v = h(i, j);
        for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
        l[i][j] = v * inverse_diagonal[j];
      }
    }
  }

  /// H^-1 b by L y = b, L^T x = y.
  Eigen::Vector4d solve(const Eigen::Vector4d& b) const {
    double y[4], x[4];
    for (int i = 0; i < 4; ++i) {
      double v = b[i];
      for (int k = 0; k < i; ++k) v -= l[i][k] * y[k];
      y[i] = v * inverse_diagonal[i];
    }
    for (int i = 3; i >= 0; --i) {
      double v = y[i];
      for (int k = i + 1; k < 4; ++k) v -= l[k][i] * x[k];
      x[i] = v * inverse_diagonal[i];
    }
    return {x[0], x[1], x[2], x[3]};
  }
};

}  // namespace

Mat3 energy_exact_rotation(const Mat3& s) {
  const double det = s.determinant();
  const double norm = s.norm();
  if (det > 1e-6 * norm * norm * norm) return polar_rotation(s, Mat3::Identity());
  return rotation_factor(s);
}

NewtonOutcome energy_newton_rotation(const Mat3& s, double a, const Mat3& warm, double tolerance,
                                     int max_iterations) {
  using Vec4 = Eigen::Vector4d;
  using Mat4 = Eigen::Matrix4d;
  NewtonOutcome out;
  const Mat4 n = horn_matrix(s.transpose());
  Vec4 q = newton_start(warm);
  double lambda = 2 * q.dot(n * q) - 2 * a * q.squaredNorm();
  bool converged = false;
  bool last_step_definite = false;  // the last step's Hessian factored by Cholesky
  for (int it = 0;; ++it) {
    const Vec4 nq = n * q;
    const double q2 = q.squaredNorm();
    const Vec4 grad = 4 * a * q2 * q - 4 * nq + 2 * lambda * q;  // eq. (5)
    const double constraint = q2 - 1;                            // eq. (6)
    if (grad.norm() / (4 * a) + std::abs(constraint) < tolerance) {
      converged = true;
      break;
    }
    if (it == max_iterations) break;
    // Bordered Newton system of eqs. (7), (8): [H 2q; 2q^T 0] [dq; dl] = -[g; c]. Near a
    // minimizer H is positive definite: Cholesky, two solves, and the Schur complement in dl.
    // Elsewhere (indefinite or singular H) the general 5x5 LU decides, or declares it singular.
    const Mat4 hessian = 4 * a * (q2 * Mat4::Identity() + 2 * q * q.transpose()) - 4 * n +
                         2 * lambda * Mat4::Identity();
    Vec4 dq;
    double dl;
    const Cholesky4 llt(hessian);
    last_step_definite = llt.ok;
    if (last_step_definite) {
      const Vec4 hg = llt.solve(grad), hq = llt.solve(q);
      dl = (constraint - 2 * q.dot(hg)) / (4 * q.dot(hq));
      dq = -(hg + 2 * dl * hq);
    } else {
      Eigen::Matrix<double, 5, 5> kkt;
      kkt.topLeftCorner<4, 4>() = hessian;
      kkt.topRightCorner<4, 1>() = 2 * q;
      kkt.bottomLeftCorner<1, 4>() = 2 * q.transpose();
      kkt(4, 4) = 0;
      Eigen::Matrix<double, 5, 1> rhs;
      rhs << -grad, -constraint;
      const Eigen::PartialPivLU<Eigen::Matrix<double, 5, 5>> lu(kkt);
      const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
      if (!(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) break;  // singular: not unique
      const Eigen::Matrix<double, 5, 1> step = lu.solve(rhs);
      dq = step.head<4>();
      dl = step[4];
    }
    if (!dq.allFinite()) break;
    const Eigen::Matrix<double, 5, 1> step = (Eigen::Matrix<double, 5, 1>() << dq, dl).finished();
    q += step.head<4>();
    lambda += step[4];
    out.iterations = it + 1;
  }
  if (converged && !last_step_definite) {
    // A minimizer has a positive definite Hessian (see header); a saddle does not. Checked here
    // unless the last step's Hessian, at a point within the tolerance, was already definite.
    const Mat4 hessian = 4 * a * (q.squaredNorm() * Mat4::Identity() + 2 * q * q.transpose()) -
                         4 * n + 2 * lambda * Mat4::Identity();
    converged = Cholesky4(hessian).ok;
  }
  if (!converged) {
    out.fell_back = true;
    out.rotation = energy_exact_rotation(s);
    return out;
  }
  out.rotation = newton_rotation(q);
  return out;
}

EnergyNewtonExtractor::EnergyNewtonExtractor(const TetMesh& mesh, const Parameters& params)
    : RotationExtractor(RotationMethod::EnergyNewton),
      mesh_(mesh),
      tolerance_(params.number("newton_tolerance")),
      max_iterations_(static_cast<int>(params.integer("newton_max_iterations"))),
      rest_(rest_moment_arms(mesh)) {}

void EnergyNewtonExtractor::extract(const std::vector<Vec3>& positions,
                                    std::vector<Mat3>& rotations) {
  stats_.iterations.resize(mesh_.tets.size());
  const int tets = mesh_.num_tets();
  const int batches =
      (tets + kNewtonLanes - 1) / kNewtonLanes;  // fixed by the mesh, not the threads
  int fallbacks = 0, inverted = 0;
  const NewtonBatchInput in{mesh_.tets.data(), rest_.data(), positions.data(), tolerance_,
                            max_iterations_};
#pragma omp parallel for schedule(static) reduction(+ : fallbacks, inverted) num_threads(threads_for(tets))
  for (int batch = 0; batch < batches; ++batch) {
    const int first = batch * kNewtonLanes;
    const NewtonBatchCounts counts = energy_newton_batch(
        in, first, std::min(kNewtonLanes, tets - first), rotations, stats_.iterations.data());
    fallbacks += counts.fallbacks;
    inverted += counts.inverted;
  }
  stats_.fallbacks = fallbacks;
  stats_.inverted = inverted;
}

EnergyExactExtractor::EnergyExactExtractor(const TetMesh& mesh)
    : RotationExtractor(RotationMethod::EnergyExact), mesh_(mesh), rest_(rest_moment_arms(mesh)) {}

void EnergyExactExtractor::extract(const std::vector<Vec3>& positions,
                                   std::vector<Mat3>& rotations) {
  stats_.iterations.assign(mesh_.tets.size(), 0);
  int inverted = 0;
#pragma omp parallel for schedule(static) reduction(+ : inverted) num_threads(threads_for(mesh_.num_tets()))
  for (int e = 0; e < mesh_.num_tets(); ++e) {
    double a = 0;
    const Mat3 s = deformed_moment(rest_[e], mesh_.tets[e], positions, a);
    inverted += s.determinant() <= 0;
    rotations[e] = energy_exact_rotation(s);
  }
  stats_.inverted = inverted;
}

RotationMethodTraits energy_newton_traits() {
  return {.name = "energy-newton",
          .make = extractor_maker<EnergyNewtonExtractor>(),
          .parameters = {{.key = "newton_tolerance",
                          .fallback = 1e-9,
                          .min = kMinTolerance,
                          .max = 0.5,
                          .meaning = "|grad_q E| / (4 a) + |q.q - 1| at which Newton stops"},
                         {.key = "newton_max_iterations",
                          .kind = ParameterSpec::Kind::Integer,
                          .fallback = 20LL,
                          .min = 1,
                          .max = 100,
                          .meaning = "Newton iterations per element before the fallback"}},
          .static_tolerances = {"newton_tolerance"},
          .tangent = TangentFamily::MomentFactor,
          .looser = {{"newton_tolerance", {1e-6, 1e-3}}},
          .in_smoke = true};
}

RotationMethodTraits energy_exact_traits() {
  return {.name = "energy-exact",
          .make = extractor_maker<EnergyExactExtractor>(),
          .tangent = TangentFamily::MomentFactor};
}

}  // namespace corofem
