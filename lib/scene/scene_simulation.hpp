#pragma once
// A scene ready to run: its problem, rotation extractor, linear solver and load schedule, built
// once. `corofem run` and the report's drivers share it; the report swaps in instrumented solvers.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "mesh/tet_mesh.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "scene/scene.hpp"

namespace corofem {

class SceneSimulation {
 public:
  /// Builds everything the scene asks for (InputError for bad input).
  explicit SceneSimulation(const Scene& scene);

  const Scene& scene() const { return scene_; }
  FeProblem& problem() { return problem_; }
  const MeshValidation& validation() const { return validation_; }
  RotationExtractor& extractor() { return *extractor_; }
  LinearSolver& solver() { return *solver_; }
  void set_solver(std::unique_ptr<LinearSolver> solver) { solver_ = std::move(solver); }
  std::unique_ptr<LinearSolver> release_solver() { return std::move(solver_); }
  /// Time spent meshing the multigrid hierarchy's coarse levels (inside the setup time).
  double coarse_meshing_ms() const { return coarse_meshing_ms_; }
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

  /// Static or dynamic, as the scene says; `on_step` follows every dynamic step. Phase times
  /// include "setup" (building) and "total".
  SimulationResult run(const std::function<void(const StepState&)>& on_step = {});

 private:
  Scene scene_;
  MeshValidation validation_;
  FeProblem problem_;
  std::unique_ptr<RotationExtractor> extractor_;
  std::optional<DynamicOptions> dynamic_;
  std::unique_ptr<LinearSolver> solver_;
  double setup_ms_ = 0;
  double coarse_meshing_ms_ = 0;
};

}  // namespace corofem
