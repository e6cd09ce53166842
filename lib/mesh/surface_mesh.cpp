#include "mesh/surface_mesh.hpp"

#include <Eigen/Geometry>

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

}  // namespace corofem
