#include "mesh/locality_order.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace corofem {
namespace {

/// Spreads the low 21 bits of x to every third bit.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

/// v[i] = old v[order[i]] (an empty v, such as absent tags, stays empty).
template <class T>
void permute(std::vector<T>& v, const std::vector<int>& order) {
  if (v.empty()) return;
  std::vector<T> out(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) out[i] = v[order[i]];
  v = std::move(out);
}

}  // namespace

void sort_for_locality(TetMesh& mesh) {
  const int nv = mesh.num_vertices();
  if (nv == 0) return;
  Vec3 lo = mesh.rest[0], hi = lo;
  for (const Vec3& x : mesh.rest) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double extent = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::uint64_t> key(nv);
  for (int v = 0; v < nv; ++v) {
    const Vec3 t = (mesh.rest[v] - lo) / extent * double((1 << 21) - 1);
    key[v] = spread_bits(std::uint64_t(t.x())) | spread_bits(std::uint64_t(t.y())) << 1 |
             spread_bits(std::uint64_t(t.z())) << 2;
  }
  std::vector<int> order(nv);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::vector<int> new_index(nv);
  for (int i = 0; i < nv; ++i) new_index[order[i]] = i;
  permute(mesh.rest, order);
  permute(mesh.node_tags, order);
  for (Tet& t : mesh.tets)
    for (int& v : t) v = new_index[v];
  // Tets by their smallest vertex: an element's scatter lands near the previous one's.
  const int nt = mesh.num_tets();
  std::vector<int> tet_order(nt);
  std::iota(tet_order.begin(), tet_order.end(), 0);
  auto smallest = [&](int e) {
    return *std::min_element(mesh.tets[e].begin(), mesh.tets[e].end());
  };
  std::stable_sort(tet_order.begin(), tet_order.end(),
                   [&](int a, int b) { return smallest(a) < smallest(b); });
  permute(mesh.tets, tet_order);
  permute(mesh.element_tags, tet_order);
}

}  // namespace corofem
