#pragma once
// What each element keeps of its rest shape, computed once (paper 4.2: element matrices stored).
#include <vector>

#include "fem/element_stiffness.hpp"

namespace corofem {

struct ElementRest {
  Mat12 stiffness;             ///< K_e
  Vec12 stiffness_times_rest;  ///< K_e x_e, so that f0_e = Q_e (K_e x_e) costs one rotation
  Mat3 rest_edge_inverse;      ///< Dm^{-1}
  double volume = 0;
};

std::vector<ElementRest> precompute_elements(const TetMesh& mesh,
                                             const std::vector<Material>& materials);

/// Deformation gradient F = Ds Dm^{-1} of element `tet` at `positions`.
Mat3 deformation_gradient(const Mat3& rest_edge_inverse, const std::vector<Vec3>& positions,
                          const Tet& tet);

}  // namespace corofem
