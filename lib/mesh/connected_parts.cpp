#include "mesh/connected_parts.hpp"

#include "core/disjoint_sets.hpp"

namespace corofem {

ConnectedParts connected_parts(const TetMesh& mesh) {
  DisjointSets joined(mesh.num_vertices());
  for (const Tet& tet : mesh.tets)
    for (int a = 1; a < 4; ++a) joined.join(tet[0], tet[a]);
  ConnectedParts parts;
  parts.of_vertex.assign(mesh.num_vertices(), -1);
  std::vector<int> part_of_root(mesh.num_vertices(), -1);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    int& part = part_of_root[joined.find(v)];
    if (part < 0) part = parts.count++;
    parts.of_vertex[v] = part;
  }
  return parts;
}

}  // namespace corofem
