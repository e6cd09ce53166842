#pragma once
// Dynamics M u'' + C u' + Ktilde u = f + f0 (paper eq. 2) by linearly implicit Euler with lumped
// mass and Rayleigh damping C = alpha M + beta Ktilde. Per step, with rotations from the current
// positions p:  (M + dt C + dt^2 Ktilde) v' = M v + dt (f + f0 - Ktilde p),  p' = p + dt v',
// with f0 - Ktilde p = -f_int(u) evaluated element-wise (see internal_forces).
// With `newton`, fully implicit Euler instead: per step Newton iterations on
//   g(v') = (1 + dt alpha) M v' + dt beta Ktilde_n v' - M v - dt (f - f_int(u + dt v')) = 0
// with the consistent tangent (fem/rotation_tangent.hpp), Ktilde_n frozen at the step's start; a
// line search on the incremental potential where the force has one, and a step that does not
// converge cut to two of dt/2 (DynamicOptions::max_step_cuts).
#include <functional>

#include "fem/fe_problem.hpp"
#include "fem/rank_view.hpp"
#include "fem/simulation_result.hpp"
#include "integrate/newton_iteration.hpp"
#include "linalg/linear_solver.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

struct StepState;

struct DynamicOptions {
  /// Off: small strain (Ktilde = K). Linearly implicit, K and A are then the same at every step:
  /// assembled and handed to the solver once (again only when the supported DOFs change), and a
  /// step is one product with K and the solve.
  bool corotational = true;
  double dt = 0.01;
  int steps = 1;
  double rayleigh_alpha = 0;  ///< mass-proportional damping (1/s)
  double rayleigh_beta = 0;   ///< stiffness-proportional damping (s)
  /// Called before each step (1-based) to set time-varying loads and supports:
  /// problem.external_force, and problem.dirichlet with the displacement prescribed at the end of
  /// the step. Without it both stay as they are.
  std::function<void(int step, FeProblem& problem)> before_step{};
  bool newton = false;  ///< fully implicit Euler by Newton (else linearly implicit)
  /// Linearly implicit: problem.stiffness holds the step's Ktilde when on_step is called (for
  /// callbacks that use it). Off, the assembly writes (dt beta + dt^2) Ktilde straight into the
  /// step's matrix, and problem.stiffness is not written.
  bool keep_stiffness = false;
  /// Per Newton step. A step that misses the tolerance is retried as two of dt/2 (supports
  /// moving halfway in the first), at most max_step_cuts halvings deep; then NotConverged.
  NewtonSettings newton_settings{};
  int max_step_cuts = 4;
  /// Newton: the Cholesky factorizations of its tangent solves (SparseLuSolve).
  Factorization factorization = Factorization::Supernodal;
  /// Linearly implicit, corotated: the iterative solve starts from the projection on the last
  /// start_history velocities (linalg/projected_start.hpp; at least 2), not from their linear
  /// extrapolation (0). Unused by small strain, whose A the solver keeps across steps.
  int start_history = 0;
  /// Linearly implicit only: the problem is this rank's part of a distributed mesh; the inverted
  /// count and the final residual are the whole body's (the solver distributed to match).
  RankView ranks{};
  /// Marks each step's phases (rotate, assemble, update, solve, ...) as sections for it.
  EventObserver* sections = nullptr;
};

/// State after each step, for records that follow a run (flutter, energy, VTU frames, timings).
struct StepState {
  int step;
  const Eigen::VectorXd& displacement;
  const Eigen::VectorXd& velocity;
  const std::vector<Mat3>& rotations;  ///< the ones this step's system used
  const std::map<std::string, double>&
      phase_ms;             ///< this step: rotate, assemble, update, solve, step
  const SolveStats& solve;  ///< newton: iterations = Newton iterations, residual = |g| / scale
};

/// The fully implicit Euler step's Newton matrix from the tangent K_t in `j`, in place:
/// j = dt^2 K_t + damping K + mass_factor M (K the problem's stiffness, M lumped), where
/// damping = dt beta and mass_factor = 1 + dt alpha (Rayleigh).
void euler_newton_matrix(const FeProblem& problem, double dt, double damping, double mass_factor,
                         BrcMatrix& j);

/// Fixed DOFs keep zero velocity. Throws NumericalFault naming the step on NaN/inf.
SimulationResult solve_dynamic(FeProblem& problem, RotationExtractor& extractor,
                               LinearSolver& solver, const DynamicOptions& options,
                               const std::function<void(const StepState&)>& on_step = {});

}  // namespace corofem
