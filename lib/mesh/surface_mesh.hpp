#pragma once
// A closed triangle surface as indexed triangles: what a body's STL describes.
#include <array>
#include <vector>

#include "core/types.hpp"

namespace corofem {

struct SurfaceMesh {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;  ///< outward-oriented (counter-clockwise from outside)

  int num_vertices() const { return static_cast<int>(points.size()); }
};

/// Area of the surface.
double surface_area(const SurfaceMesh& surface);

/// Volume enclosed by a closed, outward-oriented surface (divergence theorem).
double enclosed_volume(const SurfaceMesh& surface);

}  // namespace corofem
