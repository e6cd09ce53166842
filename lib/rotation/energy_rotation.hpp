#pragma once
// The paper's rotation extraction by energy minimization (Section 3, eqs. 3-8) and its exact
// closed-form minimizer. With S = sum_g w z_g y_g^T (= F C, quadrature of eq. 3), the energy is
// E(q) = a |q|^4 - 2 q^T N q + c, q the quaternion of Q^T (the paper's variable), a = sum w |z|^2,
// N = horn_matrix(S^T); its minimizer over unit q is N's top eigenvector (Horn 1987).
#include <Eigen/Core>
#include <Eigen/Geometry>

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
Mat3 deformed_moment(const MomentArms& rest, const Tet& tet, const std::vector<Vec3>& positions, double& a);

/// Outcome of one element's Newton solve.
struct NewtonOutcome {
  Mat3 rotation;
  int iterations = 0;
  bool fell_back = false;  ///< singular or indefinite Hessian, or no convergence: exact minimizer used
};

/// The paper's q describes Q^T: Newton starts from the conjugate of the warm rotation's
/// quaternion, and its unit q gives back Q = R(q)^T.
inline Eigen::Vector4d newton_start(const Mat3& warm) {
  const Eigen::Quaterniond start(warm);
  return {start.w(), -start.x(), -start.y(), -start.z()};
}
inline Mat3 newton_rotation(const Eigen::Vector4d& q) {
  const Eigen::Vector4d unit = q.normalized();
  return Eigen::Quaterniond(unit[0], unit[1], unit[2], unit[3]).toRotationMatrix().transpose();
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
  EnergyNewtonExtractor(const TetMesh& mesh, const RotationParams& params);
  std::string name() const override { return "energy-newton"; }
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  RotationParams params_;
  std::vector<MomentArms> rest_;
};

class EnergyExactExtractor : public RotationExtractor {
 public:
  explicit EnergyExactExtractor(const TetMesh& mesh);
  std::string name() const override { return "energy-exact"; }
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  std::vector<MomentArms> rest_;
};

}  // namespace corofem
