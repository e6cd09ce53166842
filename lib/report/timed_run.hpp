#pragma once
// One dynamic scene run for the report, instrumented: phase times of every step, solver
// statistics, and on request the oracle checks of the verification summary (the same step solved
// by CHOLMOD, the Galerkin levels against Eigen's R A R^T, energy-newton against energy-exact).
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/statistics.hpp"
#include "integrate/implicit_euler.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "report/step_roofline.hpp"

namespace corofem {

struct TimedRunOptions {
  int warmup_steps = 0;          ///< steps left out of the medians
  std::vector<int> check_steps;  ///< steps whose linear solve is checked against CHOLMOD
  bool check_operators = false;  ///< Galerkin levels and rotations against the oracles, at the end
  /// Multigrid runs with PETSc built: time PETSc's MatPtAP (numeric reuse) on the final matrix.
  bool time_matptap = false;
  /// Called after every step with the problem (for study metrics; its stiffness is the step's
  /// Ktilde); may throw to stop the run.
  std::function<void(const StepState&, const FeProblem&)> on_step;
};

struct TimedRun {
  int tets = 0, vertices = 0, levels = 1;
  std::vector<std::map<std::string, double>>
      step_ms;                     ///< per step: rotate, assemble, update, solve, step
  std::vector<SolveStats> solves;  ///< per step
  SimulationResult result;
  TetMesh mesh;                              ///< as run (rest positions, tets)
  double rest_volume = 0, final_volume = 0;  ///< sums of signed tet volumes
  /// Oracle checks (negative: not run).
  double solve_error_max = -1;     ///< |x - x_cholmod| / |x_cholmod| over check_steps
  double solve_residual_max = -1;  ///< relative residual the solver reached on those steps
  double galerkin_error_max = -1;  ///< |E_h - R A R^T|_F / |R A R^T|_F over levels (Eigen oracle)
  double rotation_error_max_rad = -1;  ///< energy-newton against energy-exact at the final state
  int rotation_elements_compared = 0;
  /// PETSc's MatPtAP in numeric-reuse mode on the run's final fine matrix and transfers, every
  /// coarse level: median ms of 5 updates after the symbolic one (negative: not run).
  double matptap_ms = -1;
  /// What a multigrid solver measured (with the coarse meshing time); none for other solvers.
  std::optional<MultigridSummary> multigrid;
  /// Per step: mean rotation iterations per element (0 for closed-form methods).
  std::vector<double> rotation_iterations;
  /// Bytes and flops per step of each phase (step_roofline.hpp) at the median iteration counts
  /// after warm-up, and the bytes of the step's main structures; empty unless a multigrid solve.
  std::map<std::string, Traffic> traffic;
  std::map<std::string, Traffic> update_traffic;  ///< the update phase's parts
  double working_set_bytes = 0;

  /// A phase's time in every step after warm-up but the oracle-checked ones.
  std::vector<double> phase_ms(const std::string& phase, int warmup) const;
  /// Median of a phase over the steps after warm-up.
  double median_ms(const std::string& phase, int warmup) const;
  /// Per phase (rotate, assemble, update, solve, step), its time in every step after warm-up
  /// but the oracle-checked ones: the evidence behind the medians, for `corofem compare`.
  nlohmann::json samples_ms(int warmup) const;
  /// Median linear iterations per step after warm-up.
  double median_iterations(int warmup) const;
  /// The roofline record of the step (step_roofline.hpp) under `roofs`; null without traffic.
  nlohmann::json roofline(int warmup, const MachineRoofs& roofs) const;
  /// Mean final displacement of the rest vertices inside box [[lo],[hi]] (zero if none).
  Vec3 probe(const nlohmann::json& box) const;
};

/// Parses `scene` (named `name` in messages) and runs it. Throws InputError, NumericalFault, or
/// whatever on_step throws.
TimedRun timed_run(const nlohmann::json& scene, const std::string& name,
                   const TimedRunOptions& options);

}  // namespace corofem
