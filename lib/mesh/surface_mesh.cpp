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

double signed_triangle_volume(const SurfaceMesh& s, const std::array<int, 3>& t) {
  return s.points[t[0]].dot(s.points[t[1]].cross(s.points[t[2]])) / 6;
}

double enclosed_volume(const SurfaceMesh& s) {
  double volume = 0;
  for (const auto& t : s.triangles) volume += signed_triangle_volume(s, t);
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

SurfaceDefects surface_defects(const SurfaceMesh& s) {
  const std::vector<int> same = welded_vertices(s);
  std::map<std::array<int, 2>, int> triangles_at;
  std::set<std::array<int, 3>> seen;
  SurfaceDefects defects;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    std::array<int, 3> corners = {same[s.triangles[t][0]], same[s.triangles[t][1]],
                                  same[s.triangles[t][2]]};
    for (int k = 0; k < 3; ++k) {
      const int a = corners[k], b = corners[(k + 1) % 3];
      ++triangles_at[{std::min(a, b), std::max(a, b)}];
    }
    std::sort(corners.begin(), corners.end());
    if (!seen.insert(corners).second) defects.coinciding_triangles.push_back(static_cast<int>(t));
  }
  for (const auto& [edge, count] : triangles_at)
    if (count == 1) defects.open_edges.push_back(edge);
  return defects;
}

}  // namespace corofem
