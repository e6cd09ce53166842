#include "multigrid/lattice_level.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace corofem {

CoarseLevel make_lattice_level(const std::vector<Vec3>& points, const std::vector<char>& fixed,
                               double cell) {
  const auto box = bounding_box(points);
  const Vec3 origin = box[0] - Vec3::Constant(1e-9 * cell);
  // Lattice vertices are keyed by integer coordinates; ids are given in order of first use.
  std::unordered_map<long long, int> id_of;
  CoarseLevel level;
  auto key = [](long long i, long long j, long long k) { return (i * 2097152 + j) * 2097152 + k; };
  std::vector<std::array<long long, 3>> coords;
  auto vertex = [&](long long i, long long j, long long k) {
    auto [it, inserted] = id_of.emplace(key(i, j, k), static_cast<int>(coords.size()));
    if (inserted) coords.push_back({i, j, k});
    return it->second;
  };
  Transfer& t = level.transfer;
  t.fine = static_cast<int>(points.size());
  t.p_start.push_back(0);
  for (int l = 0; l < t.fine; ++l) {
    if (!fixed.empty() && fixed[l]) {
      t.p_start.push_back(static_cast<int>(t.p_col.size()));
      continue;
    }
    const Vec3 local = (points[l] - origin) / cell;
    const long long c[3] = {static_cast<long long>(std::floor(local.x())),
                            static_cast<long long>(std::floor(local.y())),
                            static_cast<long long>(std::floor(local.z()))};
    double s[3] = {local.x() - c[0], local.y() - c[1], local.z() - c[2]};
    int axis[3] = {0, 1, 2};
    std::sort(axis, axis + 3, [&](int a, int b) { return s[a] > s[b]; });
    long long corner[3] = {c[0], c[1], c[2]};
    const double w[4] = {1 - s[axis[0]], s[axis[0]] - s[axis[1]], s[axis[1]] - s[axis[2]],
                         s[axis[2]]};
    std::array<std::pair<int, double>, 4> entries;
    for (int v = 0; v < 4; ++v) {
      if (v > 0) ++corner[axis[v - 1]];
      entries[v] = {vertex(corner[0], corner[1], corner[2]), w[v]};
    }
    std::sort(entries.begin(), entries.end());
    for (const auto& [i, weight] : entries)
      if (weight > 1e-14) {  // a zero weight adds no coupling, only fill
        t.p_col.push_back(i);
        t.p_weight.push_back(weight);
      }
    t.p_start.push_back(static_cast<int>(t.p_col.size()));
  }
  for (int i : t.keep_supported_coarse_vertices(static_cast<int>(coords.size())))
    level.points.push_back(origin + cell * Vec3(coords[i][0], coords[i][1], coords[i][2]));
  return level;
}

}  // namespace corofem
