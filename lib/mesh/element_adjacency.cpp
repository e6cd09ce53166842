#include "mesh/element_adjacency.hpp"

#include <algorithm>

namespace corofem {

ElementRings element_one_rings(const TetMesh& mesh) {
  std::vector<std::vector<int>> around_vertex(mesh.rest.size());
  for (int e = 0; e < mesh.num_tets(); ++e)
    for (int v : mesh.tets[e]) around_vertex[v].push_back(e);
  ElementRings rings;
  rings.start.reserve(mesh.tets.size() + 1);
  rings.start.push_back(0);
  std::vector<int> ring;
  for (const Tet& t : mesh.tets) {
    ring.clear();
    for (int v : t) ring.insert(ring.end(), around_vertex[v].begin(), around_vertex[v].end());
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    rings.elements.insert(rings.elements.end(), ring.begin(), ring.end());
    rings.start.push_back(static_cast<int>(rings.elements.size()));
  }
  return rings;
}

}  // namespace corofem
