#pragma once
// The coarse meshes of a scene's multigrid hierarchy (`analysis.hierarchy: "meshes"`): those the
// scene gives in `mesh.levels`, then the same geometry re-meshed at 2x, 4x, ... the size of the
// last one given (or of the fine mesh): the quadruped with a doubled gmsh mesh size, the surface
// too after its triangles are coarsened to that size (gmsh would keep them), the box with half
// the cells per axis, but never fewer than 2 across (a body one element thick locks in bending,
// and its coarse correction with it).
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "multigrid/hierarchy_builder.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// The spec of coarse level h >= 1 (mesh.levels[h - 1], or derived as above). Throws InputError
/// for a mesh file without enough levels (a volume file cannot be re-meshed).
MeshSpec coarse_mesh_spec(const MeshSpec& fine, int h, const std::string& scene_name);

/// Coarse levels 1 .. levels - 1 of `fine` as validated meshes (reordered where the spec says),
/// named "level h (source)"; `name` (the scene) for messages. With `fine_vertices` (the fine
/// mesh's count) they stop at the first that does not coarsen by HierarchyParams::min_coarsening
/// (the hierarchy uses lattice levels from there on); a derived surface level that gmsh cannot fill
/// ends them too, with a warning on stderr. With `fine_vertices` and `coarsening` > 0, a derived
/// quadruped or surface level is re-meshed at the size that gives it about 1/coarsening of the
/// level above's vertices: a fixed size factor coarsens a body by a ratio that grows with its
/// size, and its convergence follows the ratio (lib/docs/multigrid.md).
/// With `coarsest_limit` > 0 they stop after the first of at most that many vertices
/// (coarsest_vertex_limit), and after the last a mesh file gives.
std::vector<TetMesh> coarse_meshes(const MeshSpec& fine, int levels, const std::string& name,
                                   int fine_vertices = 0,
                                   double coarsening = HierarchyParams{}.coarsening,
                                   int coarsest_limit = 0);

/// The scene's coarse meshes when it runs multigrid on the meshes hierarchy; otherwise none.
std::vector<TetMesh> coarse_meshes(const Scene& scene, int fine_vertices);

}  // namespace corofem
