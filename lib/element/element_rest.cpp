#include "element/element_rest.hpp"

#include <cmath>

namespace corofem {

std::vector<ElementRest> precompute_elements(const TetMesh& mesh,
                                             const std::vector<Material>& materials) {
  std::vector<ElementRest> elements(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const Tet& t = mesh.tets[e];
    const Vec3 &x0 = mesh.rest[t[0]], &x1 = mesh.rest[t[1]], &x2 = mesh.rest[t[2]],
               &x3 = mesh.rest[t[3]];
    ElementRest& el = elements[e];
    el.gradient = shape_gradients(rest_edge_inverse(x0, x1, x2, x3));
    const double volume = std::abs(signed_volume(x0, x1, x2, x3));
    el.lambda_volume = volume * materials[e].lame_lambda();
    el.mu_volume = volume * materials[e].lame_mu();
  }
  return elements;
}

Mat3 deformation_gradient(const Mat3& rest_edge_inverse, const std::vector<Vec3>& positions,
                          const Tet& tet) {
  Mat3 ds;
  ds << positions[tet[1]] - positions[tet[0]], positions[tet[2]] - positions[tet[0]],
      positions[tet[3]] - positions[tet[0]];
  return ds * rest_edge_inverse;
}

}  // namespace corofem
