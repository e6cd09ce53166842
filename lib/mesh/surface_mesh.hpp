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

/// Each vertex's first vertex at the same coordinates: one index per distinct point, as an STL
/// repeats each vertex in every triangle that has it.
std::vector<int> welded_vertices(const SurfaceMesh& surface);

/// The edges that border one triangle only, as vertex pairs: the rims of the surface's holes
/// (none on a closed surface). Vertices at the same coordinates count as one (welded_vertices).
std::vector<std::array<int, 2>> open_edges(const SurfaceMesh& surface);

/// The triangles with the same three vertices as an earlier one, either way round: a repeated
/// triangle, or two bodies touching along a face (welded_vertices).
std::vector<int> coinciding_triangles(const SurfaceMesh& surface);

}  // namespace corofem
