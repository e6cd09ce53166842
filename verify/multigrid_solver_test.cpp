// Multigrid and MG-PCG (and PETSc's GAMG and hypre's BoomerAMG where this build has PETSc)
// against CHOLMOD on three meshes and the quadruped, static and dynamic; the V-cycle's
// convergence factor rho = (r_k / r_0)^(1/k) on both hierarchies; the two-grid cycle against its
// dense error-propagation operator; fixed DOFs stay exactly fixed.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>

#include "cholmod_oracle.hpp"
#include "core/errors.hpp"
#include "core/threads.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/loads.hpp"
#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "linalg/preconditioned_cg.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/scene.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"
#include "solver/petsc_solver.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

struct MeshCase {
  std::string name;
  MeshSpec spec;  ///< the fine mesh and how its coarse levels are made
  TetMesh mesh;
  std::vector<MaterialRegion> regions;
  int fixed_axis = 0;  ///< fixed: the vertices near the lowest coordinate along this axis
  /// Stationary V-cycles on the lattice crawl on curved, thin bodies (static, 500 cycles: the
  /// quadruped to 2.5e-3, the bunny to 3.4e-10, rate 0.957); MG-PCG on the same lattice converges.
  bool lattice_vcycles_stall = false;
  /// Levels 1 and 2 of the meshes hierarchy.
  std::vector<TetMesh> coarse() const { return coarse_meshes(spec, 3, name); }
};

MeshSpec box_spec(const Vec3& size, std::array<int, 3> cells) {
  MeshSpec s;
  s.box = size;
  s.cells = cells;
  return s;
}

std::vector<MeshCase> meshes() {
  std::vector<MeshCase> cases;
  for (auto [name, size, cells] : {std::tuple{"cube", Vec3(1, 1, 1), std::array{10, 10, 10}},
                                   std::tuple{"bar", Vec3(1, 0.1, 0.1), std::array{40, 4, 4}}}) {
    const MeshSpec spec = box_spec(size, cells);
    cases.push_back({name, spec, load_scene_mesh(spec), {}});
  }
  // The surface stays at hand for re-meshing the coarse levels.
  static test::TempDir dir;
  test::write_text(dir / "cube.stl", test::cube_stl(6));
  MaterialRegion stiff;
  stiff.box = {Vec3(0.5, 0, 0), Vec3(1, 1, 1)};
  stiff.young = 1e7;  // 10x the base: a heterogeneous body
  MeshSpec surface;
  surface.kind = MeshSpec::Kind::Surface;
  surface.path = dir / "cube.stl";
  surface.size = 0.12;
  cases.push_back({"gmsh-cube-heterogeneous", surface, load_scene_mesh(surface), {stiff}});
  return cases;
}

FeProblem problem_for(const MeshCase& c) {
  auto materials = materials_per_element(c.mesh, Material{1e6, 0.3, 1000}, c.regions);
  FeProblem p = make_fe_problem(c.mesh, std::move(materials));
  // Fixed: the vertices within 2% of the extent from the lowest coordinate along fixed_axis (a
  // face of the boxes, a patch of a curved body: the bunny's base).
  const auto box = bounding_box(p.mesh.rest);
  const int k = c.fixed_axis;
  const double slab = 0.02 * (box[1][k] - box[0][k]);
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v][k] < box[0][k] + slab) p.dirichlet.fix_vertex(v);
  p.external_force = gravity_load(p.mesh, p.materials, Vec3(0, -3, -9.81));
  return p;
}

AnalysisSpec analysis(const std::string& solver, double tolerance, const std::string& hierarchy,
                      bool setup_reuse = false, int coarsest_max_vertices = 0) {
  AnalysisSpec a;
  a.solver_parameters.set("setup_reuse", setup_reuse);
  a.multigrid.hierarchy.coarsest_max_vertices = coarsest_max_vertices;
  a.solver = solver_named(solver);
  a.multigrid.hierarchy.kind = *kHierarchyKinds.find(hierarchy);
  a.multigrid.hierarchy.levels = 3;
  a.tolerance = tolerance;
  return a;
}

/// The small-strain system with the supports imposed, as the static solver builds it; `b` gets
/// the matching right-hand side.
BrcMatrix small_strain_system(FeProblem& p, Eigen::VectorXd& b) {
  const std::vector<Mat3> identity(p.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd force;
  b = p.external_force;
  assemble_corotated(p.elements, p.mesh, p.assembly, identity, Eigen::VectorXd::Zero(p.num_dofs()),
                     p.stiffness, force);
  BrcMatrix system = p.stiffness;
  apply_dirichlet(p.dirichlet, system, b);
  return system;
}

/// Multigrid and MG-PCG on both hierarchies (and Jacobi-PCG) against CHOLMOD: one static linear
/// solve and three corotated dynamic steps.
void expect_solutions_equal_cholmod(const MeshCase& c) {
  const std::vector<TetMesh> coarse = c.coarse();
  struct Solver {
    const char* name;
    const char* hierarchy;
    bool setup_reuse;
    int coarsest_max_vertices = 0;
    CycleShape cycle = CycleShape::V;
  };
  std::vector<Solver> solvers = {{"multigrid", "meshes", false},
                                 {"mgpcg", "meshes", false},
                                 {"multigrid", "meshes", false, 0, CycleShape::W},
                                 {"mgpcg", "meshes", false, 0, CycleShape::W},
                                 {"multigrid", "lattice", false},
                                 {"mgpcg", "lattice", false},
                                 {"jacobi-pcg", "lattice", false},
                                 // Lattice levels below the meshes, down to 20 vertices.
                                 {"mgpcg", "meshes", false, 20}};
  if (have_petsc()) {  // the libraries users would pick instead (the hierarchy is not theirs)
    solvers.push_back({"petsc-gamg", "lattice", false});
    solvers.push_back({"hypre-boomeramg", "lattice", false});
    solvers.push_back({"petsc-mg", "meshes", false});  // PETSc's PCMG on our hierarchy
    // Their setup reused across the dynamic steps: the solves still reach the tolerance.
    solvers.push_back({"petsc-gamg", "lattice", true});
    solvers.push_back({"hypre-boomeramg", "lattice", true});
  }
  for (const auto& [name, hierarchy, setup_reuse, coarsest_max, cycle] : solvers) {
    const std::string what =
        c.name + ": " + name +
        (std::string(name).find('-') == std::string::npos || std::string(name) == "jacobi-pcg"
             ? std::string(" on ") + hierarchy
             : "") +
        (setup_reuse ? " (setup reused)" : "") +
        (coarsest_max > 0 ? " (coarsest <= " + std::to_string(coarsest_max) + " vertices)" : "") +
        (cycle == CycleShape::W ? " (W-cycle)" : "");
    auto analysis_of = [&](double tolerance, bool reuse) {
      AnalysisSpec a = analysis(name, tolerance, hierarchy, reuse, coarsest_max);
      a.multigrid.cycle = cycle;
      return a;
    };
    try {
      // Static linear: one solve of K u = f to relative residual 1e-10, which leaves a solution
      // error of ~cond(K) x 1e-10 / 1e4 << 1e-8 for these meshes.
      FeProblem p = problem_for(c);
      auto none = make_rotation_extractor(RotationMethod::None, p.mesh);
      auto direct = make_cholmod_solver();
      const SimulationResult ref = solve_static(p, *none, *direct, {false, 1, 1e-8, 1});
      auto mg = make_linear_solver(analysis_of(1e-10, false), p, coarse);
      if (c.lattice_vcycles_stall && std::string(name) == "multigrid" &&
          std::string(hierarchy) == "lattice") {
        // Says so instead of returning a solution that misses its tolerance.
        EXPECT_THROW(solve_static(p, *none, *mg, {false, 1, 1e-8, 1}), NotConverged) << what;
        continue;
      }
      const SimulationResult got = solve_static(p, *none, *mg, {false, 1, 1e-8, 1});
      EXPECT_LT((got.displacement - ref.displacement).norm(), 1e-8 * ref.displacement.norm())
          << what;
      // Fixed DOFs exactly fixed (the transfer never touches them).
      for (int d = 0; d < p.num_dofs(); ++d)
        if (p.dirichlet.fixed[d]) {
          ASSERT_EQ(got.displacement[d], 0.0) << what;
        }
      // Three corotated dynamic steps: A = M + dt^2 Ktilde changes every step.
      auto polar_a = make_rotation_extractor(RotationMethod::Polar, p.mesh);
      auto polar_b = make_rotation_extractor(RotationMethod::Polar, p.mesh);
      DynamicOptions o;
      o.steps = 3;
      o.rayleigh_alpha = 0.5;
      o.rayleigh_beta = 0.001;
      const SimulationResult dref = solve_dynamic(p, *polar_a, *direct, o);
      auto mg_dyn = make_linear_solver(analysis_of(1e-12, setup_reuse), p, coarse);
      const SimulationResult dgot = solve_dynamic(p, *polar_b, *mg_dyn, o);
      EXPECT_LT((dgot.displacement - dref.displacement).norm(), 1e-8 * dref.displacement.norm())
          << what << " dynamic";
    } catch (const std::exception& e) {
      ADD_FAILURE() << what << ": " << e.what();
    }
  }
}

/// The surface `file` of the models folder at gmsh size `size`; its path empty where the folder or
/// the file is missing (the test then skips).
MeshSpec model_surface(const std::string& file, double size) {
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::Surface;
  spec.size = size;
  const auto models = test::models_dir();
  if (!models.empty() && std::filesystem::exists(models / file)) spec.path = models / file;
  return spec;
}

TEST(MultigridSolver, StaticAndDynamicSolutionsEqualCholmod) {
  for (const MeshCase& c : meshes()) expect_solutions_equal_cholmod(c);
}

TEST(MultigridSolver, QuadrupedSolutionsEqualCholmod) {
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::Quadruped;
  spec.size = 0.1;  // about 3.7k tets; coarse levels re-meshed at 0.2 and 0.4
  expect_solutions_equal_cholmod({"quadruped", spec, load_scene_mesh(spec), {}, 0, true});
}

TEST(MultigridSolver, BunnySolutionsEqualCholmod) {
  // The small bunny (L1) over the coarsest surface (L2), as the report builds its hierarchy.
  MeshSpec spec = model_surface("bunny_L1.stl", 0.09365);
  const MeshSpec coarse = model_surface("bunny_L2.stl", 0.18579);
  if (spec.path.empty() || coarse.path.empty())
    GTEST_SKIP() << "models folder not found (set COROFEM_MODELS)";
  spec.levels = {coarse};
  expect_solutions_equal_cholmod({"bunny", spec, load_scene_mesh(spec), {}, 2, true});
}

TEST(MultigridSolver, BareSurfaceLevelsCoarsenAndSolutionsEqualCholmod) {
  // The fine bunny as a user's STL gives it, no levels: the coarse surfaces are derived from it.
  const MeshSpec spec = model_surface("bunny_L0.stl", 0.045098);
  if (spec.path.empty()) GTEST_SKIP() << "models folder not found (set COROFEM_MODELS)";
  // Its derived surfaces grown to cover the body: stationary V-cycles converge on it (not grown,
  // they stalled at a rate of 0.96 on this static problem).
  const MeshCase c{"bunny, bare surface", spec, load_scene_mesh(spec), {}, 2, true};
  FeProblem p = problem_for(c);
  const std::vector<TetMesh> coarse = coarse_meshes(spec, 3, c.name, p.mesh.num_vertices());
  ASSERT_EQ(coarse.size(), 2u);
  auto mg = make_multigrid_solver(analysis("mgpcg", 1e-8, "meshes"), p, coarse, true);
  for (const CoarseLevelOrigin& origin : mg->level_origins())
    EXPECT_EQ(origin.kind, CoarseLevelOrigin::Kind::Mesh) << origin.fallback;
  Eigen::VectorXd b;
  mg->set_matrix(small_strain_system(p, b));
  const MultigridHierarchy& h = mg->hierarchy();
  ASSERT_EQ(h.num_levels(), 3);
  for (int l = 1; l < 3; ++l) {
    // Issue 36: at least 4x fewer vertices per level and fewer nonzeros than the level above.
    EXPECT_LE(4 * h.matrix(l).block_rows, h.matrix(l - 1).block_rows) << "level " << l;
    EXPECT_LT(h.matrix(l).num_blocks(), h.matrix(l - 1).num_blocks()) << "level " << l;
  }
  expect_solutions_equal_cholmod(c);
}

TEST(MultigridSolver, LevelsSizedByVertexRatioHaveItAndSolutionsEqualCholmod) {
  // analysis.coarsening: the 11k quadruped's derived level 1 re-meshed until it has 1/ratio of
  // the fine vertices, within the 15% the search accepts. At 4.5 the doubled size (3.6x here)
  // misses, so the re-meshing is exercised; at 3 the first guess is rejected the other way.
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::Quadruped;
  spec.size = 0.0642;
  const MeshCase c{"quadruped 11k", spec, load_scene_mesh(spec), {}, 2};
  const double fine = c.mesh.num_vertices();
  const double doubled = fine / coarse_meshes(spec, 2, c.name, fine, 0)[0].num_vertices();
  FeProblem p = problem_for(c);
  auto none = make_rotation_extractor(RotationMethod::None, p.mesh);
  auto direct = make_cholmod_solver();
  const SimulationResult ref = solve_static(p, *none, *direct, {false, 1, 1e-8, 1});
  for (const double ratio : {3.0, 4.5}) {
    EXPECT_GT(std::abs(std::log(doubled / ratio)), std::log(1.15)) << ratio;
    const std::vector<TetMesh> coarse = coarse_meshes(spec, 3, c.name, fine, ratio);
    ASSERT_GE(coarse.size(), 1u);
    EXPECT_LE(std::abs(std::log(fine / coarse[0].num_vertices() / ratio)), std::log(1.15))
        << "ratio " << ratio << ": " << coarse[0].num_vertices() << " of " << fine;
    AnalysisSpec a = analysis("mgpcg", 1e-10, "meshes");
    a.multigrid.hierarchy.coarsening = ratio;
    auto mg = make_linear_solver(a, p, coarse);
    const SimulationResult got = solve_static(p, *none, *mg, {false, 1, 1e-8, 1});
    EXPECT_LT((got.displacement - ref.displacement).norm(), 1e-8 * ref.displacement.norm())
        << "ratio " << ratio;
  }
}

TEST(MultigridSolver, ChebyshevSmoothedSolutionsEqualCholmod) {
  // MG-PCG and stationary V-cycles with Chebyshev smoothing (degrees 1-3) on the meshes and the
  // lattice hierarchies: the static solve equals CHOLMOD's to 1e-8, as the Gauss-Seidel ones.
  const std::vector<MeshCase> cases = meshes();
  const MeshCase& c = cases[0];
  FeProblem p = problem_for(c);
  auto none = make_rotation_extractor(RotationMethod::None, p.mesh);
  auto direct = make_cholmod_solver();
  const SimulationResult ref = solve_static(p, *none, *direct, {false, 1, 1e-8, 1});
  for (const char* name : {"multigrid", "mgpcg"})
    for (const char* hierarchy : {"meshes", "lattice"})
      for (const int degree : {1, 2, 3}) {
        AnalysisSpec a = analysis(name, 1e-10, hierarchy);
        a.multigrid.smoother = "chebyshev";
        a.multigrid.smoother_parameters.set("chebyshev_degree", static_cast<long long>(degree));
        auto mg = make_linear_solver(a, p, c.coarse());
        const SimulationResult got = solve_static(p, *none, *mg, {false, 1, 1e-8, 1});
        EXPECT_LT((got.displacement - ref.displacement).norm(), 1e-8 * ref.displacement.norm())
            << name << " on " << hierarchy << ", degree " << degree;
      }
}

TEST(MultigridSolver, MeshThatDoesNotCoarsenIsReplacedByLatticeLevelsThatSayWhy) {
  // The level-1 "coarse" mesh is the fine mesh itself (what gmsh gives for a surface re-meshed
  // with its triangles kept, in the limit): the hierarchy uses lattice levels and says why.
  const TetMesh fine = make_box_mesh({2, 0.5, 0.5}, {32, 8, 8});  // 2673 vertices
  TetMesh same = fine;
  same.source = "the fine box again";
  HierarchyParams params;
  params.kind = HierarchyKind::Meshes;
  params.levels = 3;
  const std::vector<char> fixed(fine.num_vertices(), 0);
  const BuiltHierarchy built = build_hierarchy(fine, fixed, params, {same, same});
  ASSERT_EQ(built.levels.size(), 2u);
  int above = fine.num_vertices();
  for (std::size_t h = 0; h < 2; ++h) {
    EXPECT_EQ(built.levels[h].kind, CoarseLevelOrigin::Kind::LatticeForMesh);
    EXPECT_LT(built.transfers[h].coarse, above);
    above = built.transfers[h].coarse;
  }
  const std::string why = "mesh 'the fine box again' has " + std::to_string(fine.num_vertices()) +
                          " vertices against " + std::to_string(fine.num_vertices()) +
                          " on the level above (fewer than 1.5x fewer)";
  EXPECT_EQ(built.levels[0].fallback, why);
  EXPECT_EQ(built.levels[1].fallback, why);  // from there on
  EXPECT_TRUE(built.ended_early.empty());
  // Below a small level (at most end_below_vertices) the hierarchy ends instead, and says why.
  params.end_below_vertices = fine.num_vertices();
  const BuiltHierarchy ended = build_hierarchy(fine, fixed, params, {same, same});
  EXPECT_TRUE(ended.transfers.empty());
  EXPECT_EQ(ended.ended_early, why + ": level 0 is the coarsest");
}

TEST(MultigridSolver, CoarsestMaxVerticesAddsLatticeLevelsBelowTheMeshes) {
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::Quadruped;
  spec.size = 0.1;
  const TetMesh fine = load_scene_mesh(spec);
  const std::vector<TetMesh> coarse = coarse_meshes(spec, 3, "quadruped");
  const std::vector<char> fixed(fine.num_vertices(), 0);
  HierarchyParams params;
  params.kind = HierarchyKind::Meshes;
  params.levels = 3;
  params.min_coarsening = 1;  // gmsh's quadruped at 0.4 keeps 415 of 480 vertices: taken here
  const BuiltHierarchy meshes_only = build_hierarchy(fine, fixed, params, coarse);
  ASSERT_EQ(meshes_only.transfers.size(), 2u);
  const int mesh_coarsest = meshes_only.transfers.back().coarse;
  params.coarsest_max_vertices = mesh_coarsest / 5;
  const BuiltHierarchy built = build_hierarchy(fine, fixed, params, coarse);
  ASSERT_GT(built.transfers.size(), 2u);
  EXPECT_EQ(built.transfers[1].coarse, mesh_coarsest);  // the meshes' levels unchanged
  for (std::size_t h = 2; h < built.transfers.size(); ++h) {
    const Transfer& t = built.transfers[h];
    EXPECT_EQ(t.fine, built.transfers[h - 1].coarse);
    EXPECT_LE(2 * t.coarse, t.fine) << "level " << h + 1 << " does not halve";
    EXPECT_EQ(built.levels[h].kind, CoarseLevelOrigin::Kind::LatticeBelowCoarsest);
  }
  // This body coarsens by halves all the way: it stops at the limit.
  EXPECT_LE(built.transfers.back().coarse, params.coarsest_max_vertices);
  EXPECT_GT(built.transfers.back().coarse, params.coarsest_max_vertices / 8);
}

/// The iterative solver `name` ("multigrid", "mgpcg" on lattice levels, or "jacobi-pcg") for p, to
/// `tolerance` in at most `max_iterations`.
std::unique_ptr<LinearSolver> iterative_solver(const std::string& name, const FeProblem& p,
                                               double tolerance, int max_iterations) {
  if (name == "jacobi-pcg") return make_jacobi_pcg_solver(tolerance, max_iterations);
  MultigridParams params = multigrid_params(analysis(name, tolerance, "lattice"));
  params.max_iterations = max_iterations;
  return std::make_unique<MultigridSolver>(
      p.stiffness, build_hierarchy(p.mesh, fixed_vertices(p.dirichlet), params.hierarchy, {}),
      params, name == "mgpcg");
}

TEST(MultigridSolver, IterationCapAboveToleranceIsNotConverged) {
  // Two iterations cannot reach 1e-14: every iterative solver says so, naming itself.
  const std::vector<MeshCase> cases = meshes();
  FeProblem p = problem_for(cases[0]);
  Eigen::VectorXd b;
  const BrcMatrix system = small_strain_system(p, b);
  for (const char* name : {"multigrid", "mgpcg", "jacobi-pcg"}) {
    const std::unique_ptr<LinearSolver> solver = iterative_solver(name, p, 1e-14, 2);
    solver->set_matrix(system);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    try {
      solver->solve(b, x);
      ADD_FAILURE() << name << " returned a solution above its tolerance";
    } catch (const NotConverged& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("after 2 "), std::string::npos) << e.what();
    }
  }
}

TEST(MultigridSolver, EveryIterativeSolverReportsItsConvergenceHistory) {
  // Each iteration's relative residual goes to the observer as the solve goes (Ginkgo's
  // convergence logger): as many as the solve's iterations, the last the residual it returned,
  // and that one is the true |b - A x| / |b| of the x returned. CG's recurred residual drifts from
  // the true one by about eps times the condition number (1e-12 of |b| here), so 1% of a 1e-8
  // residual holds it; the stationary multigrid computes the true one itself.
  const std::vector<MeshCase> cases = meshes();
  FeProblem p = problem_for(cases[0]);
  Eigen::VectorXd b;
  const BrcMatrix system = small_strain_system(p, b);
  for (const char* name : {"multigrid", "mgpcg", "jacobi-pcg"}) {
    EventLog log;
    const std::unique_ptr<LinearSolver> solver = iterative_solver(name, p, 1e-8, 5000);
    solver->observe(&log);
    solver->set_matrix(system);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), r;
    const SolveStats stats = solver->solve(b, x);
    ASSERT_EQ(log.solves().size(), 1u) << name;
    const std::vector<double>& history = log.solves()[0].residuals;
    ASSERT_EQ(history.size(), static_cast<std::size_t>(stats.iterations)) << name;
    ASSERT_GT(stats.iterations, 1) << name;
    EXPECT_EQ(history.back(), stats.residual) << name;
    EXPECT_GT(history.front(), history.back()) << name;
    system.residual(b, x, r);
    EXPECT_NEAR(r.norm() / b.norm(), history.back(), 0.01 * history.back()) << name;
  }
}

TEST(MultigridSolver, SaysItselfThatItIsOne) {
  // The records, the roofline and the Galerkin oracle find the hierarchy through the solver's
  // own multigrid(), not a cast: the multigrid solvers return themselves, the others null.
  const std::vector<MeshCase> cases = meshes();
  const MeshCase& c = cases.front();
  const std::vector<TetMesh> coarse = c.coarse();
  FeProblem p = problem_for(c);
  for (const char* name : {"cholmod", "jacobi-pcg", "multigrid", "mgpcg"}) {
    SCOPED_TRACE(name);
    auto solver = make_linear_solver(analysis(name, 1e-8, "meshes"), p, coarse);
    const bool multigrid = std::string(name) == "multigrid" || std::string(name) == "mgpcg";
    EXPECT_EQ(solver->multigrid() != nullptr, multigrid);
    if (multigrid) {
      EXPECT_EQ(static_cast<const void*>(solver->multigrid()),
                static_cast<const void*>(solver.get()));
    }
  }
}

TEST(MultigridSolver, VcycleConvergenceFactor) {
  int w_cycle_cases = 0;  // cases whose hierarchy makes W differ from V (3 levels or more)
  for (const MeshCase& c : meshes()) {
    const std::vector<TetMesh> coarse = c.coarse();
    FeProblem p = problem_for(c);
    Eigen::VectorXd b;
    const BrcMatrix system = small_strain_system(p, b);
    double rho[4];
    int levels = 0;
    for (int k = 0; k < 4; ++k) {
      AnalysisSpec a = analysis("multigrid", 1e-10, k == 1 ? "lattice" : "meshes");
      a.multigrid.vcycles = 12;
      if (k == 2)
        a.multigrid.smoother = "multicolour";  // the other threaded ordering, against hybrid
      if (k == 3) a.multigrid.cycle = CycleShape::W;
      auto solver = make_linear_solver(a, p, coarse);
      solver->set_matrix(system);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
      rho[k] = solver->solve(b, x).convergence_factor;
      if (k == 3) levels = dynamic_cast<const MultigridSolver&>(*solver).hierarchy().num_levels();
      std::cout << "[ multigrid ] " << c.name << ": " << p.mesh.num_tets() << " tets, "
                << kHierarchyKinds.name(a.multigrid.hierarchy.kind) << " hierarchy, "
                << a.multigrid.smoother << " Gauss-Seidel, rho = " << rho[k] << " over 12 "
                << kCycleShapes.name(a.multigrid.cycle) << "(1,1) cycles\n";
    }
    // Nodal block GS V(1,1) with P1 transfers on 3D elasticity has a two-grid spectral radius
    // of 0.51 (nu = 0) to 0.57 (nu = 0.3) even on nested meshes (TwoGridEqualsDenseOperator);
    // measured here 0.54 (cube) and 0.87 (bar 10:1, bending-dominated).
    if (c.name == "gmsh-cube-heterogeneous")
    // A 10x stiffer half, coarse levels its surface coarsened to their size (3.5x fewer
    // vertices a level): measured 0.63 against 0.61 on the lattice levels of the same run
    // (0.52 when gmsh kept the fine surface triangles and the levels barely coarsened).
    {
      EXPECT_LE(rho[0], 1.1 * rho[1]) << c.name << ": against the lattice levels";
      // And absolutely: 0.63 measured, the nested two-grid floor of this cycle 0.57
      // (bench/nested_two_grid.py); a lattice that degrades with it must not pass.
      EXPECT_LE(rho[0], 0.7) << c.name;
    } else
      EXPECT_LE(rho[0], c.name == "bar" ? 0.9 : 0.6) << c.name;
    EXPECT_LT(rho[1], 1.0) << c.name;
    // Multicolour ordering: a different smoother, measured 0.59 (cube), 0.62 (gmsh cube), 0.96
    // (bar) against hybrid's 0.54, 0.63, 0.87: at most 15% above it.
    EXPECT_LE(rho[2], 1.15 * rho[0]) << c.name;
    // The W-cycle's coarse correction is the V-cycle's iterated towards the exact one: in the
    // energy norm it contracts at least as well (measured 0.50 against 0.54 on the cube, 0.83
    // against 0.87 on the bar); this rate is of the residual, hence 0.01. On two levels both
    // cycles solve the coarse level exactly once: the same cycle, the same rate.
    ASSERT_GE(levels, 2) << c.name;
    if (levels == 2)
      EXPECT_EQ(rho[3], rho[0]) << c.name << ": W on two levels is V";
    else
      EXPECT_LE(rho[3], rho[0] + 0.01) << c.name << " (" << levels << " levels)";
    w_cycle_cases += levels > 2;
  }
  EXPECT_GE(w_cycle_cases, 2) << "the W-cycle's bound held on fewer than the cube and the bar";
}

/// Asymptotic rate of the V-cycle on A e = 0 from a random error: the residual ratio of the
/// last of `cycles` cycles.
double asymptotic_rho(MultigridSolver& mg, const BrcMatrix& a, const std::vector<char>& fixed_dofs,
                      int cycles) {
  Eigen::VectorXd x = Eigen::VectorXd::Random(3 * a.block_rows),
                  zero = Eigen::VectorXd::Zero(x.size()), r;
  for (int d = 0; d < x.size(); ++d)
    if (fixed_dofs[d]) x[d] = 0;
  double previous = 0, ratio = 0;
  for (int k = 0; k < cycles; ++k) {
    mg.vcycle(0, zero, x, false);
    a.multiply(x, r);
    ratio = previous > 0 ? r.norm() / previous : 0;
    previous = r.norm();
  }
  return ratio;
}

/// The small-strain system of a 10 x 4 x 4 box (three lattice levels), small enough for many
/// updates.
struct BoxSystem {
  FeProblem problem = problem_for({"box",
                                   box_spec(Vec3(1, 0.4, 0.4), {10, 4, 4}),
                                   make_box_mesh({1, 0.4, 0.4}, {10, 4, 4}),
                                   {}});
  Eigen::VectorXd b;
  BrcMatrix system = small_strain_system(problem, b);
};

TEST(MultigridSolver, OverlappedFactorizationIsTheInUpdateBits) {
  // At two or more threads MG-PCG defers the coarsest factorization of every update after the
  // first to the next solve, beside its initial residual and first descent: the same operations
  // on the same data, so the same bits as one thread (where nothing is deferred: every kernel
  // gives the same bits at any count). Also through vcycle(), with a start that is already
  // converged (CG never uses the descent), and with a factorization that fails.
  BoxSystem box;
  FeProblem& p = box.problem;
  const Eigen::VectorXd& b = box.b;
  const BrcMatrix& system = box.system;
  BrcMatrix stiffer = system;  // a second matrix with the same pattern
  for (double& v : stiffer.values) v *= 1.5;
  set_items_per_thread(1);  // a small mesh, threaded anyway
  struct Run {
    Eigen::VectorXd x, cycled, restarted;
    int iterations = 0;
    bool deferred = false;
  };
  auto run = [&](int threads, CycleShape cycle) {
    const ScopedThreadCount count(threads);
    AnalysisSpec a = analysis("mgpcg", 1e-10, "lattice");
    a.multigrid.cycle = cycle;  // W: the deferred descent's ascent repeats the coarse cycles
    auto mg = make_multigrid_solver(a, p, {}, true);
    EXPECT_EQ(mg->hierarchy().num_levels(), 3) << "a W-cycle differs from V from 3 levels on";
    Run r;
    mg->set_matrix(system);
    EXPECT_FALSE(mg->update_deferred()) << "the first update analyses: never deferred";
    mg->set_matrix(stiffer);
    r.deferred = mg->update_deferred();
    r.x = Eigen::VectorXd::Zero(b.size());
    r.iterations = mg->solve(b, r.x).iterations;
    EXPECT_FALSE(mg->update_deferred());
    // The solution of the stiffer system as the start: CG stops before preconditioning.
    mg->set_matrix(stiffer);
    r.restarted = r.x;
    EXPECT_EQ(mg->solve(b, r.restarted).iterations, 0);
    mg->set_matrix(system);
    r.cycled = Eigen::VectorXd::Zero(b.size());
    mg->vcycle(0, b, r.cycled, true);
    // A failing factorization: at one thread set_matrix throws, deferred the solve does.
    BrcMatrix negative = system;
    for (double& v : negative.values) v = -v;
    EXPECT_THROW(
        {
          mg->set_matrix(negative);
          Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
          mg->solve(b, x);
        },
        NumericalFault);
    return r;
  };
  for (const CycleShape cycle : {CycleShape::V, CycleShape::W}) {
    const char* shape = kCycleShapes.name(cycle);
    const Run one = run(1, cycle);
    EXPECT_FALSE(one.deferred);
    EXPECT_GT(one.iterations, 2);
    for (const int threads : {2, 3}) {
      const Run many = run(threads, cycle);
      EXPECT_TRUE(many.deferred) << threads;
      EXPECT_EQ(many.iterations, one.iterations) << shape << ", " << threads;
      EXPECT_TRUE(many.x == one.x) << shape << ", " << threads << " threads: other bits";
      EXPECT_TRUE(many.restarted == one.x) << shape << ", " << threads;
      EXPECT_TRUE(many.cycled == one.cycled) << shape << ", " << threads;
    }
  }
  set_items_per_thread(2048);
}

TEST(MultigridSolver, TheCoarsestFactorIsKeptWhileItsOperatorBarelyMoves) {
  // E = R A R^T is linear in A, so A scaled by (1 + s) moves E by exactly s, relative: below
  // coarsest_refactor_change (3%) the factor of the last factorized E is kept, at or above it E is
  // factorized again. A kept factor is that of a nearby SPD operator, so MG-PCG still meets its
  // tolerance: the solution agrees with CHOLMOD's of the moved system within what a 1e-10 residual
  // allows (1e-7 here, far below the 1% the system moved). The decision reads only values, so at
  // two threads the bits are one thread's. A factorization that fails is never kept.
  BoxSystem box;
  FeProblem& p = box.problem;
  const Eigen::VectorXd& b = box.b;
  const BrcMatrix& system = box.system;
  const auto scaled = [&](double factor) {
    BrcMatrix m = system;
    for (double& v : m.values) v *= factor;
    return m;
  };
  set_items_per_thread(1);  // a small mesh, threaded anyway
  auto run = [&](int threads, double refactor_change) {
    const ScopedThreadCount count(threads);
    AnalysisSpec a = analysis("mgpcg", 1e-10, "lattice");
    a.multigrid.coarsest_refactor_change = refactor_change;
    EventLog log;
    auto mg = make_multigrid_solver(a, p, {}, true, &log);
    std::vector<int> factorizations;
    std::vector<Eigen::VectorXd> solutions;
    for (const double factor : {1.0, 1.01, 1.029, 1.04, 1.04}) {
      const BrcMatrix m = scaled(factor);
      mg->set_matrix(m);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
      EXPECT_LE(mg->solve(b, x).residual, 1e-10) << factor;
      const Eigen::VectorXd oracle = reference::cholmod_solve(to_eigen(m), b);
      EXPECT_LT((x - oracle).norm(), 1e-7 * oracle.norm()) << factor << ", " << threads;
      factorizations.push_back(log.count("coarsest factorization"));
      solutions.push_back(x);
    }
    EXPECT_EQ(log.count("update"), 5);
    return std::pair{factorizations, solutions};
  };
  // Kept at 1% and 2.9% from the first; refactored at 4% (3.96% from 1.0 is the last
  // factorized); kept when nothing moved.
  const auto [kept, one] = run(1, 0.03);
  EXPECT_EQ(kept, (std::vector<int>{1, 1, 1, 2, 2}));
  const auto [every, exact] = run(1, 0);
  EXPECT_EQ(every, (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_FALSE(one[1] == exact[1]) << "a kept factor is another preconditioner: other bits";
  const auto [kept_two, two] = run(2, 0.03);
  EXPECT_EQ(kept_two, kept);
  for (std::size_t k = 0; k < one.size(); ++k)
    EXPECT_TRUE(two[k] == one[k]) << "update " << k << ": other bits at two threads";
  // An indefinite operator fails to factorize; the next one, 0.1% from it, is factorized again
  // (and fails again), never solved with the failed factor. One thread: set_matrix factorizes.
  const ScopedThreadCount one_thread(1);
  AnalysisSpec a = analysis("mgpcg", 1e-10, "lattice");
  EventLog log;
  auto mg = make_multigrid_solver(a, p, {}, true, &log);
  mg->set_matrix(system);
  EXPECT_THROW(mg->set_matrix(scaled(-1)), NumericalFault);
  EXPECT_THROW(mg->set_matrix(scaled(-1.001)), NumericalFault);
  mg->set_matrix(system);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  EXPECT_LE(mg->solve(b, x).residual, 1e-10);
  EXPECT_EQ(log.count("coarsest factorization"), 2);
  set_items_per_thread(2048);
}

TEST(MultigridSolver, CoarseOperatorsAreKeptWhileTheFineStiffnessBarelyMoves) {
  // A scaled by (1 + s) moves the stiffness probe (the off-diagonal entries of the diagonal
  // blocks) by exactly s, relative: below galerkin_refresh_change (5%) the coarse operators of the
  // last refresh are kept, bit for bit; at or above it they are recomputed, E = R A R^T of the new
  // A (linear in A: 1.06 times the first). Kept, the V-cycle is still an SPD preconditioner: the
  // solutions agree with CHOLMOD's within what a 1e-10 residual allows.
  BoxSystem box;
  FeProblem& p = box.problem;
  const Eigen::VectorXd& b = box.b;
  const auto scaled = [&](double factor) {
    BrcMatrix m = box.system;
    for (double& v : m.values) v *= factor;
    return m;
  };
  AnalysisSpec a = analysis("mgpcg", 1e-10, "lattice");
  a.multigrid.galerkin_refresh_change = 0.05;
  EventLog log;
  auto mg = make_multigrid_solver(a, p, {}, true, &log);
  std::vector<int> refreshes;
  std::vector<std::vector<double>> coarse;
  for (const double factor : {1.0, 1.02, 1.049, 1.06, 1.06}) {
    const BrcMatrix m = scaled(factor);
    mg->set_matrix(m);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    EXPECT_LE(mg->solve(b, x).residual, 1e-10) << factor;
    const Eigen::VectorXd oracle = reference::cholmod_solve(to_eigen(m), b);
    EXPECT_LT((x - oracle).norm(), 1e-7 * oracle.norm()) << factor;
    refreshes.push_back(log.count("galerkin refresh"));
    coarse.push_back(mg->hierarchy().matrix(1).values);
  }
  EXPECT_EQ(refreshes, (std::vector<int>{1, 1, 1, 2, 2}));
  EXPECT_TRUE(coarse[1] == coarse[0] && coarse[2] == coarse[0]) << "kept operators moved";
  double diff = 0, size = 0;
  for (std::size_t k = 0; k < coarse[0].size(); ++k) {
    diff += std::pow(coarse[3][k] - 1.06 * coarse[0][k], 2);
    size += std::pow(coarse[3][k], 2);
  }
  EXPECT_LT(std::sqrt(diff / size), 1e-13);  // recomputed: the Galerkin product of 1.06 A
  // 0, the default: every update recomputes them.
  a.multigrid.galerkin_refresh_change = 0;
  EventLog every_log;
  auto every = make_multigrid_solver(a, p, {}, true, &every_log);
  for (const double factor : {1.0, 1.02}) every->set_matrix(scaled(factor));
  EXPECT_EQ(every_log.count("galerkin refresh"), 2);
}

TEST(MultigridSolver, AnObserverHearsEverySolveAndPartAndChangesNoBit) {
  // The solver keeps no times or logs: what a record reports comes from the observer a run
  // attaches (core/event_log.hpp). With and without one, the same bits; the observer hears each
  // update and solve once, each solve with the statistics the solve returned, and parts whose
  // times add up to no more than the wall time they were measured in, from the set-up on.
  BoxSystem box;
  FeProblem& p = box.problem;
  const Eigen::VectorXd& b = box.b;
  const BrcMatrix& system = box.system;
  BrcMatrix stiffer = system;
  for (double& v : stiffer.values) v *= 1.5;
  for (const int threads : {1, 2}) {
    const ScopedThreadCount count(threads);
    EventLog log;
    auto watched = make_multigrid_solver(analysis("mgpcg", 1e-10, "lattice"), p, {}, true, &log);
    auto unwatched = make_multigrid_solver(analysis("mgpcg", 1e-10, "lattice"), p, {}, true);
    std::vector<SolveStats> returned;
    double solve_wall_ms = 0;
    for (const BrcMatrix* a : std::vector<const BrcMatrix*>{&system, &stiffer, &system}) {
      watched->set_matrix(*a);
      unwatched->set_matrix(*a);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), y = x;
      const auto start = std::chrono::steady_clock::now();
      returned.push_back(watched->solve(b, x));
      solve_wall_ms +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      unwatched->solve(b, y);
      EXPECT_TRUE(x == y) << threads << " threads: the observer changed the bits";
    }
    ASSERT_EQ(log.solves().size(), returned.size());
    for (std::size_t k = 0; k < returned.size(); ++k) {
      EXPECT_EQ(log.solves()[k].solver, "mgpcg");
      EXPECT_EQ(log.solves()[k].iterations, returned[k].iterations);
      EXPECT_EQ(log.solves()[k].residual, returned[k].residual);
      EXPECT_EQ(log.solves()[k].rate, returned[k].convergence_factor);
    }
    EXPECT_EQ(log.count("update"), 3);
    // The first update analyses and is never deferred; at two threads the other two are.
    EXPECT_EQ(log.count("deferred update"), threads > 1 ? 2 : 0);
    const MultigridSolveParts solve = solve_parts_ms(log);
    const double parts = solve.fine_smooth + solve.fine_residual + solve.fine_transfer +
                         solve.coarse_levels + solve.coarsest;
    EXPECT_GT(solve.fine_smooth, 0);
    EXPECT_GT(solve.coarsest, 0);
    EXPECT_LE(parts * static_cast<double>(returned.size()), solve_wall_ms);
    const MultigridUpdateParts update = update_parts_ms(log);
    EXPECT_GT(update.galerkin, 0);
    EXPECT_GT(update.coarsest, 0);
    EXPECT_GT(setup_parts_ms(log).galerkin_streams, 0);
    EXPECT_GT(setup_parts_ms(log).transfers, 0);  // marked by the factory that built them
    const MultigridSummary summary = summarize(*watched, log);
    EXPECT_EQ(summary.solves, 3);
    std::vector<int> iterations;
    for (const SolveStats& r : returned) iterations.push_back(r.iterations);
    std::sort(iterations.begin(), iterations.end());
    EXPECT_EQ(summary.iterations, static_cast<double>(iterations[1]));  // the median of three
  }
}

/// TwoGridEqualsDenseOperator on one coarse mesh of the unit cube.
void two_grid_equals_dense_operator(const std::vector<TetMesh>& coarse) {
  MeshCase c{"cube", box_spec(Vec3(1, 1, 1), {4, 4, 4}), make_box_mesh({1, 1, 1}, {4, 4, 4}), {}};
  FeProblem p = problem_for(c);
  Eigen::VectorXd b;
  const BrcMatrix system = small_strain_system(p, b);
  AnalysisSpec a = analysis("multigrid", 1e-10, "meshes");
  a.multigrid.hierarchy.levels = 2;
  auto mg = make_multigrid_solver(a, p, coarse, false);
  mg->set_matrix(system);
  const Eigen::MatrixXd A = Eigen::MatrixXd(to_eigen(system));
  const Eigen::MatrixXd R = Eigen::MatrixXd(restriction_matrix(mg->hierarchy().transfer(0)));
  const int n = static_cast<int>(A.rows());
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n), U = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (j / 3 <= i / 3) L(i, j) = A(i, j);
      if (j / 3 >= i / 3) U(i, j) = A(i, j);
    }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd coarse_correction =
      I - R.transpose() * (R * A * R.transpose()).ldlt().solve(R * A);
  // Row-major LU: libgmsh carries its own PartialPivLU<MatrixXd>, and one instantiation of it in
  // this binary would be bound into gmsh's calls too (ASan: bad-free inside gmsh's Eigen).
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::PartialPivLU<RowMajorMatrix> lu_u{RowMajorMatrix(U)}, lu_l{RowMajorMatrix(L)};
  const Eigen::MatrixXd E = (I - Eigen::MatrixXd(lu_u.solve(RowMajorMatrix(A)))) *
                            coarse_correction *
                            (I - Eigen::MatrixXd(lu_l.solve(RowMajorMatrix(A))));
  Eigen::VectorXd x = Eigen::VectorXd::Random(n);
  for (int d = 0; d < n; ++d)
    if (p.dirichlet.fixed[d]) x[d] = 0;
  const Eigen::VectorXd expected = E * x;
  mg->vcycle(0, Eigen::VectorXd::Zero(n), x, false);
  // A few thousand flops per entry in another order: round-off ~1e-15 relative.
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
  const Eigen::VectorXcd eigenvalues = Eigen::EigenSolver<Eigen::MatrixXd>(E, false).eigenvalues();
  const double radius = eigenvalues.cwiseAbs().maxCoeff();
  const double measured = asymptotic_rho(*mg, system, p.dirichlet.fixed, 60);
  std::cout << "[ multigrid ] two-grid V(1,1) spectral radius " << radius << ", measured "
            << measured << "\n";
  // 60 cycles: the ratio has converged to the dominant eigenvalue within a fraction of a percent
  // unless two eigenvalues of nearly equal modulus compete (then it oscillates by a few %).
  EXPECT_NEAR(measured, radius, 0.03 * radius);
}

TEST(MultigridSolver, TwoGridEqualsDenseOperator) {
  // The oracle of the cycle: the two-grid error propagation built densely,
  //   E = (I - (D+U)^-1 A) (I - P (R A P)^-1 R A) (I - (D+L)^-1 A),  P = R^T,
  // with D, L, U the block diagonal, lower and upper parts of A. One V-cycle on A x = 0 maps e
  // to E e; and the rate measured by iterating equals E's spectral radius. The fine box in Kuhn
  // cells, two coarse levels: a gmsh mesh of the same cube (non-nested, as in the paper) and the
  // box in 2 x 2 x 2 Kuhn cells (nested: the fine space contains the coarse one).
  test::TempDir dir;
  test::write_text(dir / "cube.stl", test::cube_stl(2));
  const TetMesh non_nested = tetrahedralize_surface(dir / "cube.stl", 0.5);
  const TetMesh nested = make_box_mesh({1, 1, 1}, {2, 2, 2});
  for (const TetMesh* coarse_mesh : {&non_nested, &nested}) {
    SCOPED_TRACE(coarse_mesh == &nested ? "nested" : "non-nested");
    two_grid_equals_dense_operator({*coarse_mesh});
  }
}

}  // namespace
}  // namespace corofem
