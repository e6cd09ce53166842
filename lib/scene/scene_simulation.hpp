#pragma once
// A scene ready to run: its problem, rotation extractor, linear solver and load schedule, built
// once. `corofem run` and the report's drivers share it; the report swaps in instrumented solvers.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "mesh/rank_part.hpp"
#include "mesh/tet_mesh.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "scene/scene.hpp"

namespace corofem {

struct RankShare;

class SceneSimulation {
 public:
  /// Builds everything the scene asks for (InputError for bad input).
  explicit SceneSimulation(const Scene& scene);
  /// Under mpirun, a dynamic linearly implicit or a static scene on a PETSc solver
  /// (distributes_mesh): rank 0 alone builds the whole mesh, its loads and supports (and
  /// petsc-mg's transfers), partitions it and sends every other rank its part
  /// (scene/rank_share.hpp); no other rank ever holds the whole mesh. Each builds its element
  /// data, pattern and solver on its part: problem() is the part's, the element work is the
  /// part's, the solver distributed to match.
  SceneSimulation(const Scene& scene, int rank, int ranks);
  /// Whether `ranks` ranks would run `scene` on a distributed mesh (else replicated).
  static bool distributes_mesh(const Scene& scene, int ranks);
  /// This rank's part (its mesh is problem().mesh); none when the mesh is not distributed.
  const std::optional<RankPart>& part() const { return part_; }
  /// How the distributed mesh's vertices were split over the ranks; empty when not distributed.
  const std::string& partitioner() const { return partitioner_; }
  /// Distributed: each owned vertex's number in the scene's own vertex order (the one a run on
  /// one rank numbers and records), before the partition grouped the ranks' vertices.
  const std::vector<int>& scene_vertex_index() const { return scene_vertex_index_; }
  /// Whether this process built the whole body (one rank, or rank 0 of a distributed run).
  bool built_whole_body() const { return built_whole_body_; }

  const Scene& scene() const { return scene_; }
  FeProblem& problem() { return problem_; }
  const MeshValidation& validation() const { return validation_; }
  RotationExtractor& extractor() { return *extractor_; }
  LinearSolver& solver() { return *solver_; }
  void set_solver(std::unique_ptr<LinearSolver> solver) { solver_ = std::move(solver); }
  std::unique_ptr<LinearSolver> release_solver() { return std::move(solver_); }
  /// Time spent meshing the multigrid hierarchy's coarse levels (inside the setup time).
  double coarse_meshing_ms() const { return coarse_meshing_ms_; }
  TangentSolve tangent_solve() const;
  bool corotational() const { return scene_.analysis.formulation == Formulation::Corotational; }
  /// What `solver` (this scene's solver, or the one it wraps) measured, with the coarse meshing
  /// time; none for a solver that is not multigrid.
  std::optional<MultigridSummary> multigrid_summary(const LinearSolver& solver) const;
  /// The record's `multigrid` entry: the summary's JSON; null for other solvers.
  nlohmann::json describe_multigrid(const LinearSolver& solver) const;

  /// Dynamic runs: problem().stiffness holds each step's Ktilde when on_step is called
  /// (DynamicOptions::keep_stiffness), for callbacks that read it.
  void keep_stiffness() {
    if (dynamic_) dynamic_->keep_stiffness = true;
  }

  /// Marks the run's phases and the solver's parts as sections for `sections` (kept; counted
  /// runs: core/section_counter.hpp).
  void mark_sections(EventObserver* sections);

  /// Static or dynamic, as the scene says; `on_step` follows every dynamic step, `on_iteration`
  /// every static iteration. Phase times include "setup" (building) and "total".
  SimulationResult run(const std::function<void(const StepState&)>& on_step = {},
                       const std::function<void(const StaticIteration&)>& on_iteration = {});

 private:
  /// Rank 0 of a distributed run: builds and partitions the whole body, sends each other rank
  /// its share, returns its own.
  RankShare share_out_body(int ranks);
  /// The other ranks: their share from rank 0 (or rank 0's error, thrown).
  RankShare receive_share();
  Scene scene_;
  bool built_whole_body_ = true;
  std::optional<RankPart> part_;
  std::string partitioner_;
  std::vector<int> scene_vertex_index_;
  RankView ranks_;  ///< this rank's view of a distributed mesh; one rank's otherwise
  MeshValidation validation_;
  FeProblem problem_;
  std::unique_ptr<RotationExtractor> extractor_;
  std::optional<DynamicOptions> dynamic_;
  /// The observer this run attaches to its solver (the solver keeps no times or logs):
  /// multigrid_summary reads it. Held by pointer, so that it stays where the solver points.
  std::unique_ptr<EventLog> solver_log_ = std::make_unique<EventLog>();
  std::unique_ptr<LinearSolver> solver_;
  EventObserver* sections_ = nullptr;
  /// The solver's marks to the log and to sections_, while there is one.
  std::unique_ptr<EventFanout> solver_fanout_;
  double setup_ms_ = 0;
  double coarse_meshing_ms_ = 0;
};

}  // namespace corofem
