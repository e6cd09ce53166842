#include "fem/static_solver.hpp"

#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {

SimulationResult solve_static(FeProblem& problem, RotationExtractor& extractor,
                              LinearSolver& solver, const StaticOptions& options) {
  SimulationResult result;
  PhaseClock clock(result.timings_ms);
  IdentityExtractor small_strain;
  RotationExtractor& rotate = options.corotational ? extractor : small_strain;
  Eigen::VectorXd& u = result.displacement;
  u = Eigen::VectorXd::Zero(problem.num_dofs());
  result.rotations.assign(problem.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd f0, du = Eigen::VectorXd::Zero(problem.num_dofs());
  const int increments = options.corotational ? options.load_steps : 1;
  result.converged = true;
  for (int inc = 1; inc <= increments; ++inc) {
    const double scale = static_cast<double>(inc) / increments;
    const Eigen::VectorXd f = scale * problem.external_force;
    const double f_norm = free_norm(problem.dirichlet, f);
    bool inc_converged = false;
    for (int it = 0; it <= options.max_iterations; ++it) {
      const auto p = problem.positions(u);
      result.inverted_max = std::max(result.inverted_max, count_inverted(problem, p));
      linearize(problem, rotate, p, result.rotations, f0, clock);
      const Eigen::VectorXd r =
          f - internal_forces(problem.elements, problem.mesh, result.rotations, u);
      check_finite(problem, r, "force", "load increment " + std::to_string(inc) + ", iteration " + std::to_string(it));
      result.residual = free_norm(problem.dirichlet, r) / (f_norm > 0 ? f_norm : 1);
      // A linear solve is exact after one step; corotated steps iterate the lagged rotations.
      if (it > 0 && (!options.corotational || result.residual < options.tolerance)) {
        inc_converged = true;
        break;
      }
      if (it == options.max_iterations) break;
      // Ktilde du = r, with du taking fixed DOFs to their (scaled) prescribed values.
      DirichletConditions bc = problem.dirichlet;
      bc.value = scale * problem.dirichlet.value - u;
      BrcMatrix system = problem.stiffness;
      Eigen::VectorXd b = r;
      apply_dirichlet(bc, system, b);
      clock.time("update", [&] { solver.set_matrix(system); });
      du.setZero();
      result.linear_iterations += clock.time("solve", [&] { return solver.solve(b, du); }).iterations;
      u += du;
      ++result.iterations;
      check_finite(problem, u, "displacement",
                   "load increment " + std::to_string(inc) + ", iteration " + std::to_string(it + 1));
    }
    result.steps = inc;
    if (!inc_converged) {
      result.converged = false;
      result.message = "load increment " + std::to_string(inc) + " of " +
                       std::to_string(increments) + " did not reach tolerance " +
                       std::to_string(options.tolerance) + " in " +
                       std::to_string(options.max_iterations) + " iterations (residual " +
                       std::to_string(result.residual) + ")";
      break;
    }
  }
  return result;
}

}  // namespace corofem
