#pragma once
// What each element keeps of its rest shape, computed once (paper 4.2: element matrices stored).
#include <vector>

#include "fem/element_stiffness.hpp"

namespace corofem {

struct ElementRest {
  // K_e's blocks are V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I) (element_stiffness.hpp):
  // the internal forces apply K_e from these 14 numbers instead of reading its 144.
  std::array<Vec3, 4> gradient;  ///< g_a = grad N_a at rest
  double lambda_volume = 0;      ///< V lambda
  double mu_volume = 0;          ///< V mu
  Mat12 stiffness;             ///< K_e
  Mat3 rest_edge_inverse;      ///< Dm^{-1}
  double volume = 0;
};

std::vector<ElementRest> precompute_elements(const TetMesh& mesh,
                                             const std::vector<Material>& materials);

/// Deformation gradient F = Ds Dm^{-1} of element `tet` at `positions`.
Mat3 deformation_gradient(const Mat3& rest_edge_inverse, const std::vector<Vec3>& positions,
                          const Tet& tet);

}  // namespace corofem
