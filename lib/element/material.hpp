#pragma once
// Isotropic linear elastic materials, per element, from a base material and box regions.
#include <optional>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "mesh/vertex_selection.hpp"

namespace corofem {

struct Material {
  double young = 0;    ///< Young's modulus E (Pa), > 0
  double poisson = 0;  ///< Poisson ratio nu, in (-1, 0.5)
  double density = 0;  ///< kg/m^3, > 0 where mass is needed

  double lame_lambda() const { return young * poisson / ((1 + poisson) * (1 - 2 * poisson)); }
  double lame_mu() const { return young / (2 * (1 + poisson)); }
};

/// A box whose elements (by centroid) take the given properties; unset ones keep the base value.
struct MaterialRegion {
  AxisBox box;
  std::optional<double> young, poisson, density;
};

/// Material of every element: `base`, overridden by each region containing the element's
/// centroid, in order (later regions win).
std::vector<Material> materials_per_element(const TetMesh& mesh, const Material& base,
                                            const std::vector<MaterialRegion>& regions);

}  // namespace corofem
