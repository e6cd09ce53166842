#pragma once
// The scene's loads and prescribed motions over the steps of a dynamic run: ramps, holds and
// releases (README "Scene format": ramp_steps, release_step, moves).
#include <memory>

#include "integrate/implicit_euler.hpp"
#include "scene/scene.hpp"

namespace corofem {

class LoadSchedule {
 public:
  /// Selects the vertices of every force and move (InputError naming moves[i].box if it selects
  /// none). `problem` must come from build_problem(scene): its supports are the scene's fixed.
  /// Distributed (`ranks`): `problem` is this rank's part; a force is spread over the vertices
  /// its box selects in the whole body, and a box selecting none there is the error.
  LoadSchedule(const Scene& scene, const FeProblem& problem, const RankView& ranks = {});

  /// Sets problem.external_force and problem.dirichlet for the end of `step` (1-based).
  void apply(int step, FeProblem& problem) const;

 private:
  Eigen::VectorXd gravity_;
  std::vector<Eigen::VectorXd> forces_;  ///< each at full strength
  std::vector<LoadTiming> force_timing_;
  std::vector<MoveSpec> moves_;
  std::vector<std::vector<int>> move_vertices_;
  DirichletConditions supports_;  ///< the scene's fixed boxes
};

/// The scene's analysis as DynamicOptions, with before_step driving a LoadSchedule. Applies step
/// 1's loads and supports to `problem` now, so a solver built next sees the prescribed vertices.
/// `ranks`: as LoadSchedule's, and the options' own.
DynamicOptions dynamic_options(const Scene& scene, FeProblem& problem, RankView ranks = {});

/// The velocities a dynamic step's solve is projected on (DynamicOptions::start_history), 0 for
/// the linear extrapolation: `start: projection` where it applies, a linearly implicit corotated
/// run on an iterative solver and one process's mesh (a direct solver ignores the start; small
/// strain's solver keeps its A; a distributed mesh's rank holds part of A).
int projected_start_history(const AnalysisSpec& a, bool distributed_mesh);

}  // namespace corofem
