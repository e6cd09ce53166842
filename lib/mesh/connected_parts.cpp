#include "mesh/connected_parts.hpp"

#include <numeric>

namespace corofem {

ConnectedParts connected_parts(const TetMesh& mesh) {
  // Union-find over the vertices, halving paths on the way up.
  std::vector<int> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Tet& tet : mesh.tets)
    for (int a = 1; a < 4; ++a) {
      const int r0 = root(tet[0]), ra = root(tet[a]);
      if (r0 != ra) parent[std::max(r0, ra)] = std::min(r0, ra);
    }
  ConnectedParts parts;
  parts.of_vertex.assign(mesh.num_vertices(), -1);
  std::vector<int> part_of_root(mesh.num_vertices(), -1);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    int& part = part_of_root[root(v)];
    if (part < 0) part = parts.count++;
    parts.of_vertex[v] = part;
  }
  return parts;
}

}  // namespace corofem
