#pragma once
// analysis.solver "auto": the first solves of a run measure each candidate solver on the run's own
// systems and the run keeps the cheapest. No model of the machine or of the scene predicts which
// wins (on the bare bunny at the default stiffness Jacobi-PCG's 47 iterations a step cost less
// than MG-PCG's 10 with its Galerkin update; at 100x the stiffness it is the other way round):
// the scene on the machine is measured instead.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "linalg/linear_solver.hpp"

namespace corofem {

/// What one candidate did in the trial: per trial solve, its cost (ms: the matrix update since the
/// previous solve plus the solve) and iterations; or why it could not solve.
struct SolverTrial {
  std::string name;
  std::vector<double> ms;
  std::vector<int> iterations;
  std::string failure;  ///< the error that ended its trial (never chosen then); empty if none
};

/// A trial's cost: the least of its solves after the first `warmup_solves`; infinite for a
/// candidate that failed or has no solve past the warm-up yet.
double trial_cost(const SolverTrial& trial, int warmup_solves);

/// The record of a choice: every candidate's trial, the rule and what it kept.
struct SolverChoice {
  std::vector<SolverTrial> candidates;
  int trial_solves = 0;   ///< solves that ran every candidate
  int warmup_solves = 0;  ///< of those, the first ones left out of the comparison
  int decided_after =
      0;               ///< the solves the trial ran (fewer than trial_solves if a winner was clear)
  std::string chosen;  ///< empty while the trial runs (or if the run ended within it)
  std::string rule;
};

struct SolverTrialSettings {
  /// Each trial solve runs every candidate on the same system, from the same start. The first
  /// carries one-time set-up (the multigrid's Galerkin streams, the coarsest symbolic analysis)
  /// and is left out; the least of the other three is the candidate's cost per solve: the least of
  /// a few runs is the timing least disturbed by a shared machine.
  int trial_solves = 4;
  int warmup_solves = 1;
  /// The trial ends early, after any solve past the warm-up, once one candidate costs less than
  /// 1/clear_margin of every other: a shared machine's noise does not move a time by 2x, and a
  /// losing candidate's trial can cost a run more than the choice saves (Jacobi-PCG's 400
  /// iterations against MG-PCG's 22 on the bunny at 100x the stiffness).
  double clear_margin = 2;
};

/// A solver that runs `candidates` side by side on the first `trial_solves` solves (or until a
/// winner is clear), then keeps the one of least cost and frees the others. During the trial a
/// solve returns the first candidate's solution (the second's if the first failed), so every solve
/// meets the tolerance. `clock_ms` reads the time (default: the steady clock); a test gives its
/// own.
std::unique_ptr<LinearSolver> make_trial_solver(
    std::vector<std::unique_ptr<LinearSolver>> candidates, SolverTrialSettings settings = {},
    std::function<double()> clock_ms = {});

}  // namespace corofem
