#pragma once
// The scene's `analysis.solver` as a LinearSolver for a problem.
#include "fem/fe_problem.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// The analysis's multigrid parameters, with its tolerance.
MultigridParams multigrid_params(const AnalysisSpec& analysis);

/// How a PETSc solver of the analysis solves: for a Newton tangent (newton_tangent_by_solver) by
/// GMRES to 1e-2 x the Newton tolerance (an inexact step leaves that fraction of the last
/// residual; at least 1e-13, near rounding), at most 200 iterations before MUMPS's LU takes it
/// (past a buckling point the tangent is indefinite and AMG-preconditioned GMRES stalls; a
/// definite one converges in 20-60); otherwise CG to the scene's tolerance.
struct PetscSolveSettings {
  double tolerance;
  int max_iterations;
  bool nonsymmetric;
};
PetscSolveSettings petsc_solve_settings(const AnalysisSpec& analysis);
/// The library AMGs' own setting setup_reuse (false for a solver that declares none).
bool reuses_setup(const AnalysisSpec& analysis);

/// The analysis's solver, made by its registration (scene/solver_kind.hpp), for the problem's
/// pattern, rest positions and supports. Multigrid on the meshes hierarchy takes its levels from
/// `coarse_meshes` (scene/coarse_meshes.hpp); `observer` (core/event_observer.hpp) hears what
/// the solver marks, from its set-up on.
std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& analysis,
                                                 const FeProblem& problem,
                                                 const std::vector<TetMesh>& coarse_meshes = {},
                                                 EventObserver* observer = nullptr);

/// Multigrid (V-cycles, or the preconditioner of CG) on the analysis's hierarchy.
std::unique_ptr<MultigridSolver> make_multigrid_solver(const AnalysisSpec& analysis,
                                                       const FeProblem& problem,
                                                       const std::vector<TetMesh>& coarse_meshes,
                                                       bool as_preconditioner,
                                                       EventObserver* observer = nullptr);

/// The built-in solvers' traits, in the order of the SolverKind constants (scene/solver_kind.hpp).
std::vector<SolverTraits> builtin_solvers();

/// Per vertex: 1 if all three DOFs are fixed.
std::vector<char> fixed_vertices(const DirichletConditions& bc);

}  // namespace corofem
