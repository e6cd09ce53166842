#include "scene/solver_factory.hpp"

#include <algorithm>

#include "integrate/newton_iteration.hpp"
#include "linalg/preconditioned_cg.hpp"
#include "linalg/solver_choice.hpp"
#include "solver/petsc_solver.hpp"

namespace corofem {

MultigridParams multigrid_params(const AnalysisSpec& a) {
  MultigridParams p = a.multigrid;
  p.tolerance = a.tolerance;  // the analysis's: one tolerance, whichever solver reads it
  return p;
}

std::vector<char> fixed_vertices(const DirichletConditions& bc) {
  std::vector<char> fixed(bc.fixed.size() / 3);
  for (std::size_t v = 0; v < fixed.size(); ++v)
    fixed[v] = bc.fixed[3 * v] && bc.fixed[3 * v + 1] && bc.fixed[3 * v + 2];
  return fixed;
}

std::unique_ptr<MultigridSolver> make_multigrid_solver(const AnalysisSpec& a,
                                                       const FeProblem& problem,
                                                       const std::vector<TetMesh>& coarse_meshes,
                                                       bool as_preconditioner,
                                                       SolverObserver* observer) {
  const MultigridParams params = multigrid_params(a);
  return std::make_unique<MultigridSolver>(
      problem.stiffness,
      build_hierarchy(problem.mesh, fixed_vertices(problem.dirichlet), params.hierarchy,
                      coarse_meshes),
      params, as_preconditioner, observer);
}

PetscSolveSettings petsc_solve_settings(const AnalysisSpec& a) {
  if (newton_tangent_by_solver(a.type, a.integrator, a.formulation, a.solver))
    return {newton_tangent_tolerance(a.tolerance), 200, true};
  return {a.tolerance, 10000, false};
}

std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& a, const FeProblem& problem,
                                                 const std::vector<TetMesh>& coarse_meshes,
                                                 SolverObserver* observer) {
  if (a.solver == SolverKind::Cholmod) return make_cholmod_solver(a.factorization);
  if (a.solver == SolverKind::JacobiPcg) return make_jacobi_pcg_solver(a.tolerance, 100000);
  if (a.solver == SolverKind::Auto) {  // MG-PCG first: its solutions are the trial's
    std::vector<std::unique_ptr<LinearSolver>> candidates;
    candidates.push_back(make_multigrid_solver(a, problem, coarse_meshes, true, observer));
    candidates.push_back(make_jacobi_pcg_solver(a.tolerance, 100000));
    return make_trial_solver(std::move(candidates));
  }
  const PetscSolverKind petsc = petsc_solver_kind(a.solver);
  const PetscSolveSettings s = petsc_solve_settings(a);
  if (is_library_amg(a.solver))
    return make_petsc_solver(petsc, problem.mesh.rest, s.tolerance, s.max_iterations, {}, 1,
                             a.setup_reuse, nullptr, s.nonsymmetric);
  if (a.solver == SolverKind::PetscMg) {  // PETSc's own multigrid on our hierarchy's transfers
    if (!have_petsc())
      return make_petsc_solver(petsc, problem.mesh.rest, a.tolerance, 10000);  // says why
    const MultigridParams params = multigrid_params(a);
    return make_petsc_solver(petsc, problem.mesh.rest, s.tolerance, s.max_iterations,
                             build_hierarchy(problem.mesh, fixed_vertices(problem.dirichlet),
                                             params.hierarchy, coarse_meshes)
                                 .transfers,
                             a.multigrid.pre_smoothing, false, nullptr, s.nonsymmetric);
  }
  return make_multigrid_solver(a, problem, coarse_meshes, a.solver == SolverKind::Mgpcg, observer);
}

}  // namespace corofem
