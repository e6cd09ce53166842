#include "solver/solver_factory.hpp"

#include "solver/preconditioned_cg.hpp"

namespace corofem {

std::vector<std::string> linear_solver_names() { return {"cholmod", "multigrid", "mgpcg", "jacobi-pcg"}; }

MultigridParams multigrid_params(const AnalysisSpec& a) {
  MultigridParams p;
  p.levels = a.levels;
  p.pre_smoothing = p.post_smoothing = a.smoothing;
  p.vcycles = a.vcycles;
  p.tolerance = a.tolerance;
  p.galerkin = galerkin_method(a.galerkin);
  return p;
}

std::vector<char> fixed_vertices(const DirichletConditions& bc) {
  std::vector<char> fixed(bc.fixed.size() / 3);
  for (std::size_t v = 0; v < fixed.size(); ++v)
    fixed[v] = bc.fixed[3 * v] && bc.fixed[3 * v + 1] && bc.fixed[3 * v + 2];
  return fixed;
}

std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& a, const FeProblem& problem) {
  if (a.solver == "cholmod") return make_cholmod_solver();
  if (a.solver == "jacobi-pcg") return make_jacobi_pcg_solver(a.tolerance, 100000);
  return std::make_unique<MultigridSolver>(problem.stiffness, problem.mesh.rest,
                                           fixed_vertices(problem.dirichlet),
                                           mean_edge_length(problem.mesh), multigrid_params(a),
                                           a.solver == "mgpcg");
}

}  // namespace corofem
