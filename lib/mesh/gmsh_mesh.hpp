#pragma once
// Meshes through gmsh: volume meshes gmsh reads (.msh v2/v4) and closed surfaces (.stl) filled with
// tets (Delaunay, the recipe of the models' README).
#include <filesystem>
#include <string>
#include <vector>

#include "mesh/surface_mesh.hpp"
#include "mesh/surface_shells.hpp"
#include "mesh/tet_mesh.hpp"

namespace corofem {

/// Reads the linear tets of a volume mesh; node and element tags are kept. Throws InputError
/// naming the file: missing or unreadable, not parseable, no tets, higher-order or non-tet volume
/// elements (names the element type found), or a failed validate_mesh.
TetMesh read_volume_mesh(const std::filesystem::path& file);

/// Tetrahedralizes the volume enclosed by a closed triangle surface, keeping the surface triangles
/// as the boundary, with gmsh's Mesh.MeshSizeMax = `size`. Throws InputError naming the file: a
/// surface that is not closed (where its holes are), one that intersects itself, or gmsh's error.
TetMesh tetrahedralize_surface(const std::filesystem::path& file, double size);

/// About how many tets tetrahedralize_surface fills the shells with at `size`, erring high: what
/// its memory check counts before gmsh starts. From the bodies' volume, not their bounding box.
double expected_tets(const std::vector<SurfaceShell>& shells, double size);

/// The same for a surface given as triangles (`name` for messages).
TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double size, const std::string& name);

/// A surface file's triangles, its duplicate vertices merged as gmsh reads them. Throws InputError
/// naming the file, and where its holes are if it is not closed.
SurfaceMesh read_surface(const std::filesystem::path& file);

}  // namespace corofem
