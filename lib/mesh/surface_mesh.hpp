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

/// One triangle's term of the divergence theorem: the signed volume of the tet it spans with the
/// origin, positive when the triangle faces away from the origin.
double signed_triangle_volume(const SurfaceMesh& surface, const std::array<int, 3>& triangle);

/// Volume enclosed by a closed, outward-oriented surface (divergence theorem).
double enclosed_volume(const SurfaceMesh& surface);

/// Each vertex's first vertex at the same coordinates: one index per distinct point, as an STL
/// repeats each vertex in every triangle that has it.
std::vector<int> welded_vertices(const SurfaceMesh& surface);

/// What keeps a surface from being filled with tets. Vertices at the same coordinates count as
/// one (welded_vertices).
struct SurfaceDefects {
  /// The edges that border one triangle only, as vertex pairs: the rims of the surface's holes.
  std::vector<std::array<int, 2>> open_edges;
  /// The triangles with the same three vertices as an earlier one, either way round: a repeated
  /// triangle, or two bodies touching along a face.
  std::vector<int> coinciding_triangles;
};

/// The surface's defects, found in one pass over its welded triangles: none on a closed surface.
SurfaceDefects surface_defects(const SurfaceMesh& surface);

}  // namespace corofem
