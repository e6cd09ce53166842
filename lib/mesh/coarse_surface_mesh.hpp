#pragma once
// A coarse tet mesh of a body given by its surface: the surface coarsened to the mesh size first
// (surface_simplification.hpp), then filled by gmsh (gmsh_mesh.hpp).
#include <filesystem>

#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace corofem {

/// The surface file's body at gmsh size `size`, its triangles first coarsened to about the
/// spacing `size` (area / (sqrt(3)/2 size^2) vertices, as a triangulation of equilateral
/// triangles of edge `size` has), then grown outward to cover the body (covering_moves; half or a
/// quarter as far, or not at all, where gmsh finds the grown surface intersecting itself). The
/// mesh's source names the file, both surface sizes and the growth. Throws InputError naming the
/// file where gmsh cannot fill even the ungrown surface.
TetMesh tetrahedralize_coarsened_surface(const std::filesystem::path& file, double size);

/// As above, of the surface already read from `file` (a hierarchy reads it once for all levels).
TetMesh tetrahedralize_coarsened_surface(const SurfaceMesh& fine, const std::filesystem::path& file,
                                         double size);

/// The fewest vertices a coarsened surface keeps: a coarser one no longer follows the body (a
/// bunny of 20 vertices), and a level made of it slows the cycle more than it saves.
inline constexpr int kMinCoarsenedSurfaceVertices = 50;

/// The vertices the surface keeps, coarsened to `size` (as above).
int coarsened_surface_vertices(const SurfaceMesh& fine, double size);

}  // namespace corofem
