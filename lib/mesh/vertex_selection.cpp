#include "mesh/vertex_selection.hpp"

namespace corofem {

bool AxisBox::contains(const Vec3& p) const {
  const double tol = 1e-9 * std::max(1.0, (hi - lo).norm());
  return (p.array() >= lo.array() - tol).all() && (p.array() <= hi.array() + tol).all();
}

std::vector<int> vertices_in_box(const std::vector<Vec3>& points, const AxisBox& box) {
  std::vector<int> selected;
  for (int v = 0; v < static_cast<int>(points.size()); ++v)
    if (box.contains(points[v])) selected.push_back(v);
  return selected;
}

}  // namespace corofem
