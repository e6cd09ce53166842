#include "fem/element_partition.hpp"

namespace corofem {

double RowPartition::duplication() const {
  std::size_t visits = 0;
  for (const auto& list : elements) visits += list.size();
  std::size_t distinct = 0;  // elements appear once per part that owns one of their vertices
  std::vector<char> seen;
  for (const auto& list : elements)
    for (int e : list) {
      if (static_cast<std::size_t>(e) >= seen.size()) seen.resize(e + 1, 0);
      distinct += !seen[e];
      seen[e] = 1;
    }
  return distinct > 0 ? static_cast<double>(visits) / static_cast<double>(distinct) - 1.0 : 0.0;
}

RowPartition partition_rows(const std::vector<Tet>& tets, int num_vertices, int parts) {
  if (parts < 1) parts = 1;
  std::vector<long long> prefix(num_vertices + 1, 0);
  for (const Tet& t : tets)
    for (int v : t) ++prefix[v + 1];
  for (int v = 0; v < num_vertices; ++v) prefix[v + 1] += prefix[v];
  RowPartition partition;
  partition.row_begin = balanced_ranges(prefix, parts);
  partition.elements.resize(parts);
  std::vector<int> part_of(num_vertices);
  for (int p = 0; p < parts; ++p)
    for (int v = partition.row_begin[p]; v < partition.row_begin[p + 1]; ++v) part_of[v] = p;
  for (int e = 0; e < static_cast<int>(tets.size()); ++e) {
    int seen[4];  // parts of one element, without repeats
    int count = 0;
    for (int v : tets[e]) {
      const int p = part_of[v];
      bool repeat = false;
      for (int k = 0; k < count; ++k) repeat |= seen[k] == p;
      if (!repeat) {
        seen[count++] = p;
        partition.elements[p].push_back(e);
      }
    }
  }
  return partition;
}

}  // namespace corofem
