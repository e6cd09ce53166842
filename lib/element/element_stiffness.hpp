#pragma once
// Linear tetrahedron: shape gradients, volume and the 12x12 small-strain stiffness K_e.
#include <Eigen/Core>
#include <array>

#include "core/types.hpp"
#include "element/material.hpp"

namespace corofem {

/// Inverse of the rest edge matrix Dm = [x1-x0, x2-x0, x3-x0]. Row i-1 is the gradient of the
/// barycentric shape function N_i (i = 1..3); grad N_0 = -(sum of the rows). F = Ds * Dm^{-1}.
Mat3 rest_edge_inverse(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

/// The rest shape-function gradients g_a = grad N_a, a = 0..3 (rows of Dm^{-1}, g_0 minus their
/// sum).
std::array<Vec3, 4> shape_gradients(const Mat3& rest_edge_inverse);
/// K_e with 3x3 blocks K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I), g = grad N,
/// DOF order (vertex a, component i) -> 3a+i. Symmetric PSD with the 6 rigid modes as null space.
Mat12 element_stiffness(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                        const Material& material);
/// The same K_e from the gradients and V lambda, V mu.
Mat12 gradient_stiffness(const std::array<Vec3, 4>& g, double lambda_volume, double mu_volume);

}  // namespace corofem
