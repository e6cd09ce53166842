#pragma once
// Static equilibrium f_int(u) = f_ext. Linear: one solve with Ktilde = K. Corotational: the load in
// increments; per increment iterate {extract rotations at x + u, assemble Ktilde and f0, solve
// Ktilde u = f + f0 - Ktilde x} until |f - f_int(u)| / |f| < tolerance (the rotations are lagged,
// the standard corotational fixed point; each solve is exact for the current rotations).
// With `newton`: per increment, Newton iterations on f_int(u) = f with the consistent tangent
// (fem/rotation_tangent.hpp; solved as TangentSolve says), converging quadratically where the
// lagged ones crawl;
// an increment whose full Newton steps do not converge is halved and retried.
#include <functional>
#include <string>

#include "fem/fe_problem.hpp"
#include "fem/rank_view.hpp"
#include "fem/simulation_result.hpp"
#include "linalg/linear_solver.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// Where a static run stands after one of its iterations, for progress lines.
struct StaticIteration {
  long long increment = 1;   ///< the load increment being solved, 1-based, of `increments`
  long long increments = 1;  ///< the increments the load is split into (doubled by each cut)
  int iteration = 0;         ///< iterations taken in this increment
  double residual = 0;       ///< |f - f_int(u)|_free / |f|
  bool converged = false;    ///< the increment's answer is accepted
  bool cut = false;          ///< the increment missed the tolerance and is retried as two halves
  /// "load increment 3 of 8": how messages and progress lines name the increment.
  std::string name() const {
    return "load increment " + std::to_string(increment) + " of " + std::to_string(increments);
  }
};

/// How static Newton solves its tangent: by the serial sparse factorizations; by `solver` itself,
/// made for non-symmetric matrices (PETSc's GMRES), on one process or a distributed mesh; or by
/// flexible GMRES preconditioned by `solver` on the tangent's symmetric part (corofem's multigrid:
/// integrate/preconditioned_gmres_solve.hpp).
enum class TangentSolve { Factored, BySolver, PreconditionedBySolver };

struct StaticOptions {
  bool corotational = true;
  int load_steps = 1;
  double tolerance = 1e-8;
  int max_iterations = 100;  ///< per increment
  bool newton = false;
  /// The problem is this rank's part of a distributed mesh; the residual norms and the inverted
  /// count are the whole body's (the solver distributed to match; with Newton, a solver made for
  /// non-symmetric matrices: its GMRES solves the corotated tangent).
  RankView ranks{};
  /// Newton: how the tangent is solved (see TangentSolve).
  TangentSolve tangent_solve = TangentSolve::Factored;
  /// Called after every iteration and when an increment converges (progress).
  std::function<void(const StaticIteration&)> on_iteration{};
  /// Newton, TangentSolve::Factored: the Cholesky factorizations of its tangent (SparseLuSolve).
  Factorization factorization = Factorization::Supernodal;
  /// Marks each iteration's phases as sections for it.
  EventObserver* sections = nullptr;
};

/// Never throws for non-convergence: result.converged says it (NumericalFault for NaN/inf).
SimulationResult solve_static(FeProblem& problem, RotationExtractor& extractor,
                              LinearSolver& solver, const StaticOptions& options);

}  // namespace corofem
