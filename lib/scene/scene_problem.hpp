#pragma once
// From a parsed scene to a ready FeProblem: mesh, materials, loads, supports.
#include "fem/fe_problem.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/rank_part.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// Builds the scene's mesh (generated box, gmsh volume mesh, or tetrahedralized surface).
TetMesh load_scene_mesh(const MeshSpec& spec);

/// The scene's body before its element data: the mesh (built, ordered for locality, validated),
/// a material per element, the fixed vertices and the external force (gravity and forces).
struct SceneBody {
  TetMesh mesh;
  std::vector<Material> materials;
  std::vector<int> fixed_vertices;  ///< ascending
  Eigen::VectorXd external_force;   ///< per DOF
};

/// Throws InputError naming the scene key when a fixed or force box selects no vertex, or when a
/// static scene's supports leave a rigid motion free (fewer than three non-collinear fixed
/// vertices).
SceneBody build_body(const Scene& scene, MeshValidation* validation = nullptr);

/// The body's FeProblem: element data, pattern, mass, supports and loads.
FeProblem make_problem(SceneBody body);

/// Renumbers the body's vertices: vertex v becomes new_index[v] (its mesh already renumbered so,
/// by group_vertices_by_part), with its support and its force.
void renumber_supports_and_loads(SceneBody& body, const std::vector<int>& new_index);

/// The body of a rank's part of `whole`: the part's mesh (moved out of `part`), its tets'
/// materials, its fixed vertices and its rows of the force.
SceneBody body_part(const SceneBody& whole, RankPart& part);

/// Everything a run needs: make_problem(build_body(scene, validation)).
FeProblem build_problem(const Scene& scene, MeshValidation* validation = nullptr);

}  // namespace corofem
