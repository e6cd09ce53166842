#pragma once
// The consistent tangent of the corotated force f_e = Q K_e (Q^T x_e - X_e): besides Q K_e Q^T
// (the paper's Ktilde, which treats Q as constant) it has the terms of the rotation's derivative,
//   df_e = dQ K_e (Q^T x_e - X_e) + Q K_e dQ^T x_e + Q K_e Q^T dx_e.
// dQ/dx in closed form per method family: Q = rotation factor of a map L linear in the element's
// positions (L = F for the polar methods, L = S = F C, the quadrature moment of eq. 3, for the
// energy methods) differentiates as dQ = Q [w]x, (tr(U) I - U) w = axial(Q^T dL - dL^T Q),
// U = Q^T L; the Gram-Schmidt frame (qr) by the chain rule through its normalizations.
// The tangent is non-symmetric unless the force is conservative (polar: symmetric).
#include <array>
#include <string>
#include <vector>

#include "fem/fe_problem.hpp"
#include "rotation/element_quadrature.hpp"
#include "rotation/rotation_method.hpp"

namespace corofem {

/// dQ[3a + c] = dQ / dx_{a,c}: derivative of an element's rotation by component c of its vertex a.
using RotationJacobian = std::array<Mat3, 12>;

/// Derivative of the rotation factor Q of L = Q U (U = Q^T L symmetric, proper or sign-fixed) in
/// direction dL. Where tr(U) I - U is singular (two singular values summing to zero) the
/// derivative does not exist; it returns zero there.
Mat3 rotation_factor_derivative(const Mat3& q, const Mat3& l, const Mat3& dl);

/// Whether the corotated force with this method's rotations is the gradient of elastic_energy
/// (its traits): with Q the rotation factor of F itself (polar; polar-fixed, its reflection moved
/// into the stretch) the rotation's variation does no work (an asymmetry of 1e-16 measured); the
/// identity trivially. Mueller2016 and polar-smoothed only approach it.
inline bool force_has_potential(RotationMethod method) {
  return method.traits().force_has_potential;
}

/// |J - J^T|_F / |J|_F of an element force Jacobian: 0 for a conservative force.
double asymmetry(const Mat12& j);

class RotationTangent {
 public:
  /// For the rotation `method` on problem's mesh.
  RotationTangent(const FeProblem& problem, RotationMethod method);

  /// Whether dQ is the derivative of the method's own rotation (its traits' tangent_exact).
  /// polar-smoothed averages over neighbours, a coupling left out here: its tangent is the one of
  /// polar (Newton converges linearly, not quadratically). mueller2016 and energy-newton iterate to
  /// polar(F) and the energy minimizer: their tangent is the one of that limit.
  bool exact() const { return exact_; }
  /// "polar of F", "rotation factor of S = F C", "Gram-Schmidt frame", "identity".
  const std::string& model() const { return model_; }

  void rotation_jacobian(int e, const std::vector<Vec3>& positions, const Mat3& q,
                         RotationJacobian& dq) const;

  /// d f_e / d x_e (12 x 12) of element e at `positions` with rotation q.
  Mat12 element_jacobian(int e, const std::vector<Vec3>& positions, const Mat3& q) const;

  /// The assembled tangent sum_e d f_e / d x into `out` (problem.stiffness's pattern).
  void assemble(const std::vector<Vec3>& positions, const std::vector<Mat3>& rotations,
                BrcMatrix& out) const;

 private:
  const FeProblem& problem_;
  TangentFamily family_;
  bool exact_ = true;
  std::string model_;
  /// dL/dx_{a,c} = e_c h_a^T: h_a per element and vertex (PolarOfF: shape gradients; MomentFactor:
  /// quadrature moments).
  std::vector<std::array<Vec3, 4>> h_;
  std::vector<Mat3> rest_frame_;  ///< GramSchmidt: the rest frame
};

}  // namespace corofem
