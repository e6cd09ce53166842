#include "fem/assembly_map.hpp"

#include <algorithm>

#include "core/threads.hpp"

namespace corofem {

BrcMatrix make_stiffness_pattern(const TetMesh& mesh, AssemblyMap& map) {
  std::vector<std::vector<int>> columns(mesh.num_vertices());
  for (const Tet& t : mesh.tets)
    for (int a : t)
      for (int b : t) columns[a].push_back(b);
  for (auto& c : columns) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  BrcMatrix k = make_brc_pattern(mesh.num_vertices(), columns);
  map.block.resize(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        map.block[e][4 * a + b] = k.find(mesh.tets[e][a], mesh.tets[e][b]);
  map.first.assign(mesh.tets.size(), 0);
  std::vector<char> seen(k.num_blocks(), 0);
  for (int e = 0; e < mesh.num_tets(); ++e)
    for (int ab = 0; ab < 16; ++ab)
      if (!seen[map.block[e][ab]]) {
        seen[map.block[e][ab]] = 1;
        map.first[e] |= static_cast<std::uint16_t>(1u << ab);
      }
  map.diagonal.resize(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) map.diagonal[v] = k.find(v, v);
  // As many parts as threads the assembly will use (threads_for its elements): a part more than
  // that visits its boundary elements twice on the same thread, for nothing (lib/docs/threads.md).
  map.rows = partition_rows(mesh.tets, mesh.num_vertices(), threads_for(mesh.num_tets()));
  return k;
}

}  // namespace corofem
