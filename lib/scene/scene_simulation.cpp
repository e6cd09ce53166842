#include "scene/scene_simulation.hpp"

#include <chrono>
#include <numeric>

#include "core/errors.hpp"
#include "io/solver_record.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/load_schedule.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"
#include "solver/mpi_launch.hpp"
#include "solver/petsc_solver.hpp"
#include "solver/vertex_partition.hpp"

namespace corofem {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// A number that differs, but for a coincidence, between two meshes: their sizes, coordinates and
/// connectivity, each vertex and tet weighted by its index.
double fingerprint(const TetMesh& mesh) {
  double sum = mesh.num_vertices() + 1e-3 * mesh.num_tets();
  for (int v = 0; v < mesh.num_vertices(); ++v)
    sum += (v % 97 + 1) * (mesh.rest[v].x() + 2 * mesh.rest[v].y() + 3 * mesh.rest[v].z());
  for (int t = 0; t < mesh.num_tets(); ++t)
    sum += (t % 89 + 1) * 1e-6 * (mesh.tets[t][0] + 2 * mesh.tets[t][1] + 3 * mesh.tets[t][2]);
  return sum;
}

/// The body's vertices in PT-Scotch's parts, each made a contiguous range (a rank's rows of
/// PETSc's matrices); equal shares of the locality order where it cannot split a mesh this small.
/// Returns each rank's first vertex (ranks + 1 entries); `new_index`: every vertex's new number.
std::vector<int> partition_body(SceneBody& body, int ranks, std::vector<int>& new_index,
                                std::string& partitioner) {
  const int vertices = body.mesh.num_vertices();
  if (const std::vector<int> parts = partition_vertices(body.mesh, ranks); !parts.empty()) {
    const std::vector<int> first = group_vertices_by_part(body.mesh, parts, ranks, new_index);
    renumber_supports_and_loads(body, new_index);
    partitioner = "PT-Scotch (PETSc MatPartitioning)";
    return first;
  }
  partitioner = "equal shares of the locality order";
  new_index.resize(vertices);
  std::iota(new_index.begin(), new_index.end(), 0);
  std::vector<int> first(ranks + 1);
  for (int r = 0; r <= ranks; ++r) first[r] = rank_share_start(vertices, r, ranks);
  return first;
}

}  // namespace

SceneSimulation::SceneSimulation(const Scene& scene) : scene_(scene) {
  const auto start = std::chrono::steady_clock::now();
  problem_ = build_problem(scene_, &validation_);
  const AnalysisSpec& a = scene_.analysis;
  extractor_ = make_rotation_extractor(corotational() ? a.rotation : RotationMethod::None,
                                       problem_.mesh, a.rotation_params);
  if (a.type == AnalysisType::Dynamic) dynamic_ = dynamic_options(scene_, problem_);
  const auto meshing = std::chrono::steady_clock::now();
  const std::vector<TetMesh> coarse = coarse_meshes(scene_, problem_.mesh.num_vertices());
  coarse_meshing_ms_ = ms_since(meshing);
  solver_ = make_linear_solver(a, problem_, coarse);
  setup_ms_ = ms_since(start);
}

bool SceneSimulation::distributes_mesh(const Scene& scene, int ranks) {
  const AnalysisSpec& a = scene.analysis;
  return corofem::distributes_mesh(a.integrator, a.solver, ranks);
}

SceneSimulation::SceneSimulation(const Scene& scene, int rank, int ranks) : scene_(scene) {
  if (!distributes_mesh(scene, ranks))
    throw InputError("scene '" + scene.name + "' does not run on a distributed mesh");
  const auto start = std::chrono::steady_clock::now();
  const AnalysisSpec& a = scene_.analysis;
  std::vector<Transfer> transfers;
  {
    SceneBody whole = build_body(scene_, &validation_);
    // Every rank built the body on its own (a generator, a file, gmsh): they must agree before
    // the partition numbers one body's vertices for all.
    if (!agrees_on_every_rank(fingerprint(whole.mesh)))
      throw NumericalFault("scene '" + scene.name + "': the ranks built different meshes (" +
                           whole.mesh.source +
                           "); a distributed run needs the same mesh on every rank");
    std::vector<int> new_index;
    const std::vector<int> first = partition_body(whole, ranks, new_index, partitioner_);
    const int begin = first[rank], end = first[rank + 1];
    scene_vertex_index_.resize(end - begin);
    for (int v = 0; v < whole.mesh.num_vertices(); ++v)
      if (new_index[v] >= begin && new_index[v] < end)
        scene_vertex_index_[new_index[v] - begin] = v;
    if (a.solver == SolverKind::PetscMg) {  // PETSc keeps each rank's rows of them
      const auto meshing = std::chrono::steady_clock::now();
      const std::vector<TetMesh> coarse = coarse_meshes(scene_, whole.mesh.num_vertices());
      coarse_meshing_ms_ = ms_since(meshing);
      std::vector<char> fixed(whole.mesh.num_vertices(), 0);
      for (int v : whole.fixed_vertices) fixed[v] = 1;
      transfers =
          build_hierarchy(whole.mesh, fixed, multigrid_params(a).hierarchy, coarse).transfers;
    }
    // polar-smoothed averages over a ring of tets per pass: the part holds as many more rings.
    const int rings = corotational() && a.rotation == RotationMethod::PolarSmoothed
                          ? a.rotation_params.smoothing_passes
                          : 0;
    part_ = rank_part_of_range(whole.mesh, begin, end, rings);
    problem_ = make_problem(body_part(whole, *part_));
  }  // the whole body is freed here
  extractor_ = make_rotation_extractor(corotational() ? a.rotation : RotationMethod::None,
                                       problem_.mesh, a.rotation_params);
  ranks_ = RankView{part_->owned_vertices, part_->owned_tet, sum_over_ranks};
  if (a.type == AnalysisType::Dynamic) dynamic_ = dynamic_options(scene_, problem_, ranks_);
  solver_ = make_petsc_solver(petsc_solver_kind(a.solver), problem_.mesh.rest, a.tolerance, 10000,
                              std::move(transfers), a.smoothing, a.setup_reuse, &*part_);
  setup_ms_ = ms_since(start);
}

std::optional<MultigridSummary> SceneSimulation::multigrid_summary(
    const LinearSolver& solver) const {
  const auto* mg = dynamic_cast<const MultigridSolver*>(&solver);
  if (!mg) return std::nullopt;
  MultigridSummary s = summarize(*mg);
  s.setup.coarse_meshes = coarse_meshing_ms_;
  return s;
}

nlohmann::json SceneSimulation::describe_multigrid(const LinearSolver& solver) const {
  const std::optional<MultigridSummary> s = multigrid_summary(solver);
  return s ? to_json(*s) : nlohmann::json(nullptr);
}

SimulationResult SceneSimulation::run(const std::function<void(const StepState&)>& on_step) {
  const auto start = std::chrono::steady_clock::now();
  const AnalysisSpec& a = scene_.analysis;
  SimulationResult result =
      dynamic_ ? solve_dynamic(problem_, *extractor_, *solver_, *dynamic_, on_step)
               : solve_static(problem_, *extractor_, *solver_,
                              {corotational(), a.load_steps, a.tolerance, a.max_iterations,
                               a.integrator == Integrator::Newton, ranks_});
  result.timings_ms["setup"] = setup_ms_;
  result.timings_ms["total"] = setup_ms_ + ms_since(start);
  return result;
}

}  // namespace corofem
