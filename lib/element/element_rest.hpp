#pragma once
// What each element keeps of its rest shape, computed once. The paper (4.2) stores the element
// matrices; the 14 numbers K_e is made of are enough (corotated_assembly.cpp), a tenth of the
// bytes.
#include <vector>

#include "element/element_stiffness.hpp"

namespace corofem {

struct ElementRest {
  // K_e's blocks are V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I)
  // (element_stiffness.hpp): the assembly and the internal forces apply K_e from these 14 numbers
  // instead of reading its 144. Nothing else is kept (112 bytes, not K_e's 1152): the assembly
  // streams every element once a step from memory (the Galerkin stream has evicted them), so each
  // byte here is a byte of its traffic; Dm^{-1} is rebuilt from the gradients where it is needed.
  std::array<Vec3, 4> gradient;  ///< g_a = grad N_a at rest
  double lambda_volume = 0;      ///< V lambda
  double mu_volume = 0;          ///< V mu

  /// K_e, built from the above (for the Newton tangent and the oracles).
  Mat12 stiffness() const { return gradient_stiffness(gradient, lambda_volume, mu_volume); }
  /// Dm^{-1}: its rows are g_1, g_2, g_3 (shape_gradients), the same numbers.
  Mat3 rest_edge_inverse() const {
    Mat3 b;
    b << gradient[1].transpose(), gradient[2].transpose(), gradient[3].transpose();
    return b;
  }
};

std::vector<ElementRest> precompute_elements(const TetMesh& mesh,
                                             const std::vector<Material>& materials);

/// Deformation gradient F = Ds Dm^{-1} of element `tet` at `positions`.
Mat3 deformation_gradient(const Mat3& rest_edge_inverse, const std::vector<Vec3>& positions,
                          const Tet& tet);

}  // namespace corofem
