#include "mesh/surface_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace corofem {

double surface_area(const SurfaceMesh& s) {
  double area = 0;
  for (const auto& t : s.triangles)
    area += 0.5 * (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]).norm();
  return area;
}

double enclosed_volume(const SurfaceMesh& s) {
  double volume = 0;
  for (const auto& t : s.triangles)
    volume += s.points[t[0]].dot(s.points[t[1]].cross(s.points[t[2]])) / 6;
  return volume;
}

std::vector<int> welded_vertices(const SurfaceMesh& s) {
  std::map<std::tuple<double, double, double>, int> first_at;
  std::vector<int> same(s.points.size());
  for (std::size_t v = 0; v < s.points.size(); ++v)
    same[v] =
        first_at
            .try_emplace({s.points[v].x(), s.points[v].y(), s.points[v].z()}, static_cast<int>(v))
            .first->second;
  return same;
}

std::vector<std::array<int, 2>> open_edges(const SurfaceMesh& s) {
  const std::vector<int> same = welded_vertices(s);
  std::map<std::array<int, 2>, int> triangles_at;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = same[t[k]], b = same[t[(k + 1) % 3]];
      ++triangles_at[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::array<int, 2>> open;
  for (const auto& [edge, count] : triangles_at)
    if (count == 1) open.push_back(edge);
  return open;
}

std::vector<int> coinciding_triangles(const SurfaceMesh& s) {
  const std::vector<int> same = welded_vertices(s);
  std::set<std::array<int, 3>> seen;
  std::vector<int> coinciding;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    std::array<int, 3> corners = {same[s.triangles[t][0]], same[s.triangles[t][1]],
                                  same[s.triangles[t][2]]};
    std::sort(corners.begin(), corners.end());
    if (!seen.insert(corners).second) coinciding.push_back(static_cast<int>(t));
  }
  return coinciding;
}

}  // namespace corofem
