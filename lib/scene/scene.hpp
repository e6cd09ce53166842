#pragma once
// A scene: what to simulate and how (README "Scene format"). Parsing validates every key and
// range; the harness builds nothing a scene does not ask for.
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "element/material.hpp"
#include "integrate/implicit_euler.hpp"
#include "mesh/vertex_selection.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/analysis_settings.hpp"

namespace corofem {

struct MeshSpec {
  enum class Kind { File, Surface, Box, Quadruped } kind = Kind::Box;
  std::filesystem::path path;  ///< File, Surface: resolved against the scene's folder
  double size = 0;             ///< Surface, Quadruped: gmsh Mesh.MeshSizeMax
  Vec3 box = Vec3::Ones();     ///< Box: extents
  std::array<int, 3> cells{1, 1, 1};
  bool reorder = false;  ///< sort vertices and tets for locality (mesh/locality_order.hpp)
  /// Box, Quadruped: the tets it will give (the memory check's); 0 where only meshing tells.
  double estimated_tets = 0;
  /// Surface: coarsen the surface's triangles to `size` before filling it (the derived coarse
  /// levels; gmsh keeps a surface's triangles, scene/coarse_meshes.hpp).
  bool simplify_surface = false;
  /// Coarser meshes of the same body for the multigrid hierarchy, finest first (`mesh.levels`);
  /// levels beyond them are re-meshed (scene/coarse_meshes.hpp).
  std::vector<MeshSpec> levels;
};

/// When a load acts in a dynamic run: full strength from step ramp_steps on (linear ramp from
/// step 0), and nothing from release_step on (0: never released).
struct LoadTiming {
  int ramp_steps = 0;
  int release_step = 0;
  /// Load factor at the end of `step` (1-based).
  double factor(int step) const;
};

struct ForceSpec {
  AxisBox box;
  Vec3 total = Vec3::Zero();
  LoadTiming timing;
};

/// Prescribed motion of the vertices in a box (dynamic only): at factor s the displacement is
/// s translate + (Rot(axis, s degrees) - I)(x - center); after release_step they are free.
struct MoveSpec {
  AxisBox box;
  Vec3 translate = Vec3::Zero();
  Vec3 axis = Vec3::UnitX();
  Vec3 center = Vec3::Zero();
  double degrees = 0;
  LoadTiming timing;
};

/// The `analysis` keys that belong to the multigrid solvers (ignored, with a warning, by others):
/// the hierarchy's and the cycle's, and every registered smoother's own (SmootherTraits).
std::vector<std::string> multigrid_analysis_keys();

/// The multigrid keys solver 'petsc-mg' cannot honour (PETSc's PCMG runs its own V-cycle of
/// Chebyshev-Jacobi smoothing and its own Galerkin product): refused in a scene, dropped by
/// drop_unused_multigrid_keys. The smoothers' own keys among them.
std::vector<std::string> keys_petsc_mg_cannot_honour();

/// The multigrid's defaults with one level: what an analysis holds until its scene says more
/// (the parser sizes the hierarchy of a solver that builds one).
inline MultigridParams one_level_multigrid() {
  MultigridParams p;
  p.hierarchy.levels = 1;
  return p;
}

struct AnalysisSpec {
  AnalysisType type = AnalysisType::Static;
  Formulation formulation = Formulation::Corotational;
  /// Dynamic default: linear-implicit (the paper's scheme); static default: newton (sparse LU),
  /// as the lagged iterations stall short of tight tolerances for the energy methods.
  Integrator integrator = Integrator::Newton;
  RotationMethod rotation = RotationMethod::Polar;
  /// The rotation method's own settings, as its registration declares them
  /// (RotationMethodTraits::parameters), under analysis.rotation_params.
  Parameters rotation_params;
  SolverKind solver = SolverKind::Cholmod;
  /// The multigrid's settings, held as its own parameters (one place for each): the hierarchy's
  /// (kind: meshes, the default where the mesh can be re-meshed or `mesh.levels` gives them, or
  /// lattice; levels as the scene gives them, or at most kSizedHierarchyMaxLevels down to
  /// coarsest_vertices where it gives none), the smoother and its own settings, the cycle, the
  /// Galerkin method, the coarsest factor's refactor change; `smoothing` sets both smoothing
  /// counts. Its tolerance is the analysis's (multigrid_params).
  MultigridParams multigrid = one_level_multigrid();
  /// Dynamic, linearly implicit, corotated, iterative solvers on one process: the solve's start
  /// (start_history: the velocities projected on, 2..16).
  SolveStart start = SolveStart::Extrapolation;
  int start_history = 4;
  double dt = 0.01;
  int steps = 1;
  int load_steps = 1;
  double tolerance = 1e-8;
  /// The solver's own settings, as its registration declares them (SolverTraits::parameters):
  /// petsc-gamg's and hypre-boomeramg's setup_reuse.
  Parameters solver_parameters{};
  int max_iterations = 100;
  /// Dynamic Newton: halvings of a step that does not converge (DynamicOptions::max_step_cuts).
  int max_step_cuts = DynamicOptions{}.max_step_cuts;
  /// CHOLMOD's factorization for the `cholmod` solver and Newton's tangent (the multigrid's
  /// coarsest level stays supernodal: its operator is denser).
  Factorization factorization = Factorization::Supernodal;
  double rayleigh_alpha = 0, rayleigh_beta = 0;
};

struct OutputSpec {
  bool rotations = false;
  std::optional<std::filesystem::path> vtu;  ///< resolved against the scene's folder
};

struct Scene {
  std::string name;  ///< file name, for messages
  MeshSpec mesh;
  Material material;
  std::vector<MaterialRegion> regions;
  std::vector<AxisBox> fixed;
  Vec3 gravity = Vec3::Zero();
  std::vector<ForceSpec> forces;
  std::vector<MoveSpec> moves;
  AnalysisSpec analysis;
  OutputSpec output;
  nlohmann::json raw;  ///< the scene as given, copied into results
};

/// Erases the multigrid keys from a scene's `analysis` JSON unless its solver (cholmod where
/// unset) is a multigrid one, which would warn about them, and those petsc-mg cannot honour (which
/// it refuses) for petsc-mg: for tools that switch a scene's solver.
void drop_unused_multigrid_keys(nlohmann::json& analysis);

/// Parses and validates; relative paths resolve against `base_dir`. Throws InputError naming
/// `name` and the key.
Scene parse_scene(const nlohmann::json& json, const std::filesystem::path& base_dir,
                  const std::string& name);

/// Reads a scene file (InputError for a missing file or invalid JSON, with line and column).
Scene load_scene(const std::filesystem::path& file);

}  // namespace corofem
