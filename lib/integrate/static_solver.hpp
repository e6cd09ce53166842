#pragma once
// Static equilibrium f_int(u) = f_ext. Linear: one solve with Ktilde = K. Corotational: the load in
// increments; per increment iterate {extract rotations at x + u, assemble Ktilde and f0, solve
// Ktilde u = f + f0 - Ktilde x} until |f - f_int(u)| / |f| < tolerance (the rotations are lagged,
// the standard corotational fixed point; each solve is exact for the current rotations).
// With `newton`: per increment, Newton iterations on f_int(u) = f with the consistent tangent
// (fem/rotation_tangent.hpp, sparse LU), converging quadratically where the lagged ones crawl;
// an increment whose full Newton steps do not converge is halved and retried.
#include "fem/fe_problem.hpp"
#include "fem/rank_view.hpp"
#include "fem/simulation_result.hpp"
#include "linalg/linear_solver.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

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
  /// Newton: the tangent goes to `solver` (made for non-symmetric matrices: PETSc's GMRES), on one
  /// process or a distributed mesh; otherwise to the serial sparse factorizations.
  bool tangent_by_solver = false;
};

/// Never throws for non-convergence: result.converged says it (NumericalFault for NaN/inf).
SimulationResult solve_static(FeProblem& problem, RotationExtractor& extractor,
                              LinearSolver& solver, const StaticOptions& options);

}  // namespace corofem
