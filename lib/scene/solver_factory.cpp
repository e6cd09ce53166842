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
                                                       EventObserver* observer) {
  const MultigridParams params = multigrid_params(a);
  BuiltHierarchy built = in_section(observer, kSolverParts.name(SolverPart::Transfers), [&] {
    return build_hierarchy(problem.mesh, fixed_vertices(problem.dirichlet), params.hierarchy,
                           coarse_meshes);
  });
  return std::make_unique<MultigridSolver>(problem.stiffness, std::move(built), params,
                                           as_preconditioner, observer);
}

PetscSolveSettings petsc_solve_settings(const AnalysisSpec& a) {
  if (newton_tangent_by_solver(a.type, a.integrator, a.formulation, a.solver))
    return {newton_tangent_tolerance(a.tolerance), 200, true};
  return {a.tolerance, 10000, false};
}

bool reuses_setup(const AnalysisSpec& a) {
  return a.solver_parameters.has("setup_reuse") && a.solver_parameters.flag("setup_reuse");
}

std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& a, const FeProblem& problem,
                                                 const std::vector<TetMesh>& coarse_meshes,
                                                 EventObserver* observer) {
  std::unique_ptr<LinearSolver> solver =
      a.solver.traits().make({a, problem, coarse_meshes, observer});
  solver->observe(observer);
  return solver;
}

namespace {

/// A PETSc solver of the analysis; petsc-mg on corofem's hierarchy's transfers.
std::unique_ptr<LinearSolver> make_petsc(const SolverRequest& r) {
  const AnalysisSpec& a = r.analysis;
  const PetscSolverKind kind = *a.solver.traits().petsc;
  const PetscSolveSettings s = petsc_solve_settings(a);
  if (kind != PetscSolverKind::Mg)
    return make_petsc_solver(kind, r.problem.mesh.rest, s.tolerance, s.max_iterations, {}, 1,
                             reuses_setup(a), nullptr, s.nonsymmetric);
  if (!have_petsc())
    return make_petsc_solver(kind, r.problem.mesh.rest, a.tolerance, 10000);  // says why
  const MultigridParams params = multigrid_params(a);
  return make_petsc_solver(kind, r.problem.mesh.rest, s.tolerance, s.max_iterations,
                           build_hierarchy(r.problem.mesh, fixed_vertices(r.problem.dirichlet),
                                           params.hierarchy, r.coarse_meshes)
                               .transfers,
                           a.multigrid.pre_smoothing, false, nullptr, s.nonsymmetric);
}

/// The library AMGs' own setting: keep the first matrix's set-up across the steps.
const ParameterSpec kSetupReuse{
    .key = "setup_reuse",
    .kind = ParameterSpec::Kind::Flag,
    .fallback = false,
    .meaning =
        "petsc-gamg: keep the first matrix's interpolation; hypre-boomeramg: its whole "
        "first hierarchy (CG still runs on each step's matrix)"};

}  // namespace

std::vector<SolverTraits> builtin_solvers() {
  // The memory model's bytes per tet: peak RSS of dynamic runs over the libraries' 80 MB
  // (scene/memory_estimate.hpp), rounded up.
  const auto multigrid = [](bool preconditioner) {
    return [preconditioner](const SolverRequest& r) -> std::unique_ptr<LinearSolver> {
      return make_multigrid_solver(r.analysis, r.problem, r.coarse_meshes, preconditioner,
                                   r.observer);
    };
  };
  return {
      {.name = "cholmod",
       .make = [](const SolverRequest& r) { return make_cholmod_solver(r.analysis.factorization); },
       .factorizes = true},
      {.name = "multigrid",
       .make = multigrid(false),
       .multigrid = true,
       .builds_hierarchy = true,
       .preconditions_gmres = true,
       .bytes_per_tet = 1.5e3,
       .gmres_bytes_per_tet = 900},
      {.name = "mgpcg",
       .make = multigrid(true),
       .multigrid = true,
       .builds_hierarchy = true,
       .preconditions_gmres = true,
       .bytes_per_tet = 1.5e3,
       .gmres_bytes_per_tet = 900},
      {.name = "jacobi-pcg",
       .make =
           [](const SolverRequest& r) {
             return make_jacobi_pcg_solver(r.analysis.tolerance, 100000);
           },
       .bytes_per_tet = 1.3e3},
      {.name = "petsc-gamg",
       .make = make_petsc,
       .parameters = {kSetupReuse},
       .petsc = PetscSolverKind::Gamg,
       .bytes_per_tet = 2.0e3},
      {.name = "hypre-boomeramg",
       .make = make_petsc,
       .parameters = {kSetupReuse},
       .petsc = PetscSolverKind::BoomerAmg,
       .bytes_per_tet = 3.1e3},
      {.name = "petsc-mg",
       .make = make_petsc,
       .multigrid = true,
       .builds_hierarchy = true,
       .petsc = PetscSolverKind::Mg,
       .bytes_per_tet = 1.85e3},
      // MG-PCG first: its solutions are the trial's (linalg/solver_choice.hpp).
      {.name = "auto",
       .make =
           [multigrid](const SolverRequest& r) {
             std::vector<std::unique_ptr<LinearSolver>> candidates;
             candidates.push_back(multigrid(true)(r));
             candidates.push_back(make_jacobi_pcg_solver(r.analysis.tolerance, 100000));
             return make_trial_solver(std::move(candidates));
           },
       .builds_hierarchy = true,
       .bytes_per_tet = 1.5e3 + 1.3e3},  // both candidates, through its trial
  };
}

}  // namespace corofem
