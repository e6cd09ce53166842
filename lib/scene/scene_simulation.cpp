#include "scene/scene_simulation.hpp"

#include <chrono>
#include <exception>
#include <numeric>

#include "core/errors.hpp"
#include "integrate/preconditioned_gmres_solve.hpp"
#include "io/solver_record.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/load_schedule.hpp"
#include "scene/rank_share.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"
#include "solver/mpi_launch.hpp"
#include "solver/petsc_solver.hpp"
#include "solver/vertex_partition.hpp"

namespace corofem {
namespace {

/// How rank 0 tells the others that building the body failed (broadcast_status).
constexpr int kInputFailure = 2, kOtherFailure = 1;

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
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
  AnalysisSpec solver_analysis = a;  // the multigrid as static Newton's GMRES preconditioner
  if (tangent_solve() == TangentSolve::PreconditionedBySolver)
    solver_analysis.tolerance = kTangentPreconditionerTolerance;
  solver_ = make_linear_solver(solver_analysis, problem_, coarse, solver_log_.get());
  setup_ms_ = ms_since(start);
}

bool SceneSimulation::distributes_mesh(const Scene& scene, int ranks) {
  const AnalysisSpec& a = scene.analysis;
  return corofem::distributes_mesh(a.type, a.integrator, a.solver, ranks);
}

SceneSimulation::SceneSimulation(const Scene& scene, int rank, int ranks) : scene_(scene) {
  if (!distributes_mesh(scene, ranks))
    throw InputError("scene '" + scene.name + "' does not run on a distributed mesh");
  const auto start = std::chrono::steady_clock::now();
  const AnalysisSpec& a = scene_.analysis;
  RankShare share = rank == 0 ? share_out_body(ranks) : receive_share();
  built_whole_body_ = rank == 0;
  part_ = std::move(share.part);
  scene_vertex_index_ = std::move(share.scene_vertex_index);
  problem_ = make_problem(std::move(share.body));
  extractor_ = make_rotation_extractor(corotational() ? a.rotation : RotationMethod::None,
                                       problem_.mesh, a.rotation_params);
  ranks_ = RankView{part_->owned_vertices, part_->owned_tet, sum_over_ranks, max_over_ranks};
  if (a.type == AnalysisType::Dynamic) dynamic_ = dynamic_options(scene_, problem_, ranks_);
  const PetscSolveSettings s = petsc_solve_settings(a);  // static Newton: the tangent by GMRES
  solver_ = make_petsc_solver(*a.solver.traits().petsc, problem_.mesh.rest, s.tolerance,
                              s.max_iterations, std::move(share.transfers),
                              a.multigrid.pre_smoothing, reuses_setup(a), &*part_, s.nonsymmetric);
  setup_ms_ = ms_since(start);
}

RankShare SceneSimulation::share_out_body(int ranks) {
  // Everything that can fail runs before the first share is sent, and its outcome goes to every
  // rank: the others then stop with rank 0's error instead of waiting for a share.
  const AnalysisSpec& a = scene_.analysis;
  std::optional<SceneBody> whole;
  std::vector<int> first, new_index;
  std::vector<Transfer> transfers;
  std::exception_ptr failure;
  int status = 0;
  std::string message;
  try {
    whole = build_body(scene_, &validation_);
    first = partition_body(*whole, ranks, new_index, partitioner_);
    if (a.solver == SolverKind::PetscMg) {  // each rank gets its rows of the finest one
      const auto meshing = std::chrono::steady_clock::now();
      const std::vector<TetMesh> coarse = coarse_meshes(scene_, whole->mesh.num_vertices());
      coarse_meshing_ms_ = ms_since(meshing);
      std::vector<char> fixed(whole->mesh.num_vertices(), 0);
      for (int v : whole->fixed_vertices) fixed[v] = 1;
      transfers =
          build_hierarchy(whole->mesh, fixed, multigrid_params(a).hierarchy, coarse).transfers;
    }
  } catch (const InputError& e) {
    failure = std::current_exception();
    status = kInputFailure;
    message = e.what();
  } catch (const std::exception& e) {
    failure = std::current_exception();
    status = kOtherFailure;
    message = e.what();
  }
  broadcast_status(status, message);
  if (failure) std::rethrow_exception(failure);
  // An averaging method (polar-smoothed: a ring of tets per pass) needs that many more rings.
  const RotationMethodTraits& method = a.rotation.traits();
  const int rings = corotational() && method.halo_rings ? method.halo_rings(a.rotation_params) : 0;
  std::vector<int> scene_vertex(new_index.size());
  for (std::size_t v = 0; v < new_index.size(); ++v)
    scene_vertex[new_index[v]] = static_cast<int>(v);
  RankPartCutter parts(whole->mesh, first, rings);
  for (int r = 1; r < ranks; ++r)
    send_bytes(r, pack_rank_share(make_rank_share(*whole, scene_vertex, parts.cut(r), transfers)));
  return make_rank_share(*whole, scene_vertex, parts.cut(0), transfers);
}  // the whole body is freed here

RankShare SceneSimulation::receive_share() {
  int status = 0;
  std::string message;
  broadcast_status(status, message);
  if (status == kInputFailure) throw InputError(message);  // rank 0 says it
  if (status != 0) throw NumericalFault("rank 0: " + message);
  return unpack_rank_share(receive_bytes(0));
}

std::optional<MultigridSummary> SceneSimulation::multigrid_summary(
    const LinearSolver& solver) const {
  const MultigridSolver* mg = solver.multigrid();
  if (!mg) return std::nullopt;
  MultigridSummary s = summarize(*mg, *solver_log_);
  s.setup.coarse_meshes = coarse_meshing_ms_;
  return s;
}

nlohmann::json SceneSimulation::describe_multigrid(const LinearSolver& solver) const {
  const std::optional<MultigridSummary> s = multigrid_summary(solver);
  return s ? to_json(*s) : nlohmann::json(nullptr);
}

/// How static Newton solves its tangent: the solver's GMRES (PETSc), GMRES preconditioned by the
/// solver (corofem's multigrid), or the sparse factorizations.
TangentSolve SceneSimulation::tangent_solve() const {
  const AnalysisSpec& a = scene_.analysis;
  if (!newton_tangent_by_solver(a.type, a.integrator, a.formulation, a.solver))
    return TangentSolve::Factored;
  return is_petsc_solver(a.solver) ? TangentSolve::BySolver : TangentSolve::PreconditionedBySolver;
}

void SceneSimulation::mark_sections(EventObserver* sections) {
  sections_ = sections;
  if (dynamic_) dynamic_->sections = sections;
  solver_fanout_ =
      sections
          ? std::make_unique<EventFanout>(std::vector<EventObserver*>{solver_log_.get(), sections})
          : nullptr;
  solver_->observe(sections ? static_cast<EventObserver*>(solver_fanout_.get())
                            : solver_log_.get());
}

SimulationResult SceneSimulation::run(
    const std::function<void(const StepState&)>& on_step,
    const std::function<void(const StaticIteration&)>& on_iteration) {
  const auto start = std::chrono::steady_clock::now();
  const AnalysisSpec& a = scene_.analysis;
  SimulationResult result =
      dynamic_ ? solve_dynamic(problem_, *extractor_, *solver_, *dynamic_, on_step)
               : solve_static(problem_, *extractor_, *solver_,
                              {corotational(), a.load_steps, a.tolerance, a.max_iterations,
                               a.integrator == Integrator::Newton, ranks_, tangent_solve(),
                               on_iteration, a.factorization, sections_});
  result.timings_ms["setup"] = setup_ms_;
  result.timings_ms["total"] = setup_ms_ + ms_since(start);
  return result;
}

}  // namespace corofem
