#include "element/material.hpp"

namespace corofem {

std::vector<Material> materials_per_element(const TetMesh& mesh, const Material& base,
                                            const std::vector<MaterialRegion>& regions) {
  std::vector<Material> materials(mesh.tets.size(), base);
  if (regions.empty()) return materials;
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const Tet& t = mesh.tets[e];
    Vec3 centroid = 0.25 * (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]] + mesh.rest[t[3]]);
    for (const MaterialRegion& region : regions) {
      if (!region.box.contains(centroid)) continue;
      if (region.young) materials[e].young = *region.young;
      if (region.poisson) materials[e].poisson = *region.poisson;
      if (region.density) materials[e].density = *region.density;
    }
  }
  return materials;
}

}  // namespace corofem
