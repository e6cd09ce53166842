#pragma once
// Vertex sets picked by axis-aligned boxes (fixed vertices, loaded vertices, material regions).
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct AxisBox {
  Vec3 lo, hi;
  /// Inclusive, with a tolerance of 1e-9 of the box diagonal so that faces of a generated box
  /// (coordinates computed as L*i/n) are caught by boxes written with round numbers.
  bool contains(const Vec3& p) const;
};

/// Indices of the vertices inside the box.
std::vector<int> vertices_in_box(const std::vector<Vec3>& points, const AxisBox& box);

}  // namespace corofem
