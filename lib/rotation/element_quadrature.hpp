#pragma once
// The paper's rotation energy (eq. 3) E_e(Q) = int_e |Q^T (x + u - c) - (x - c0)|^2 dx by
// quadrature. d is affine in x on a linear tet, so |d|^2 is quadratic: the 4-point rule of degree 2
// (barycentric (a, b, b, b) and permutations, a = (5 + 3 sqrt 5)/20, b = (5 - sqrt 5)/20, weights
// V/4; Keast 1986) integrates it exactly with the fewest points.
#include <array>

#include "element/element_stiffness.hpp"

namespace corofem {

inline constexpr double kQuadratureA = 0.58541019662496845446;
inline constexpr double kQuadratureB = 0.13819660112501051518;

/// Offsets from the centroid at the 4 quadrature points of the tet (v0..v3), and the weight V/4.
struct QuadraturePoints {
  std::array<Vec3, 4> offset;
  double weight = 0;
};

/// Quadrature points of the tet with vertices v, offsets taken from the vertex centroid (the
/// centre of mass of a uniform tet).
QuadraturePoints quadrature_points(const std::array<Vec3, 4>& v, double volume);

/// The rule collapsed for the moment of eq. 3: the deformed offsets are z_g = (A - B)(p_g - p_mean)
/// and the rest ones y_g = (A - B)(x_g - x_mean), so S = sum_g w z_g y_g^T = sum_v p_v h_v^T with
/// h_v = w (A - B) y_v (= dS/dp_v; sum_v h_v = 0 makes S translation-invariant), and
/// a = sum_g w |z_g|^2 = c sum_v |p_v - p_mean|^2 with c = w (A - B)^2. 13 numbers per element.
struct MomentArms {
  std::array<Vec3, 4> h;
  double c = 0;
};
MomentArms moment_arms(const QuadraturePoints& rest);

/// E_e(Q) evaluated by the rule: sum_g w |Q^T z_g - y_g|^2 (z deformed, y rest offsets).
double rotation_energy(const Mat3& q, const QuadraturePoints& rest,
                       const QuadraturePoints& deformed);

}  // namespace corofem
