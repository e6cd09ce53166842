#pragma once
// From a parsed scene to a ready FeProblem: mesh, materials, loads, supports.
#include "fem/fe_problem.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// Builds the scene's mesh (generated box, gmsh volume mesh, or tetrahedralized surface).
TetMesh load_scene_mesh(const MeshSpec& spec);

/// Everything a run needs. Throws InputError naming the scene key when a fixed or force box
/// selects no vertex, or when a static scene's supports leave a rigid motion free (fewer than
/// three non-collinear fixed vertices).
FeProblem build_problem(const Scene& scene, MeshValidation* validation = nullptr);

}  // namespace corofem
