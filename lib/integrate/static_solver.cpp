#include "integrate/static_solver.hpp"

#include <memory>

#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "fem/rotation_tangent.hpp"
#include "integrate/newton_iteration.hpp"
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
  Eigen::VectorXd elastic, du = Eigen::VectorXd::Zero(problem.num_dofs());
  const int increments = options.corotational ? options.load_steps : 1;
  result.converged = true;
  std::unique_ptr<RotationTangent> tangent;
  std::unique_ptr<SparseLuSolve> lu;
  BrcMatrix jacobian_matrix;
  if (options.newton && options.corotational) {
    tangent = std::make_unique<RotationTangent>(problem, rotate.name());
    lu = std::make_unique<SparseLuSolve>(problem.stiffness);
    jacobian_matrix = problem.stiffness;
  }
  for (int inc = 1; inc <= increments; ++inc) {
    const double scale = static_cast<double>(inc) / increments;
    const Eigen::VectorXd f = scale * problem.external_force;
    const double f_norm = free_norm(problem.dirichlet, f);
    bool inc_converged = false;
    if (tangent) {
      // g(u) = f_int(u) - f, J = d f_int / du; fixed DOFs at their (scaled) prescribed values.
      for (int i = 0; i < u.size(); ++i)
        if (problem.dirichlet.fixed[i]) u[i] = scale * problem.dirichlet.value[i];
      std::vector<Vec3> positions;
      const auto residual = [&](const Eigen::VectorXd& z) {
        positions = problem.positions(z);
        result.inverted_max = std::max(result.inverted_max, count_inverted(problem, positions));
        clock.time("rotate", [&] { rotate.extract(positions, result.rotations); });
        return Eigen::VectorXd(internal_forces(problem, result.rotations, z) - f);
      };
      const auto jacobian = [&](BrcMatrix& j) {
        clock.time("assemble", [&] { tangent->assemble(positions, result.rotations, j); });
      };
      const NewtonReport report =
          newton_iterate(u, residual, jacobian, problem.dirichlet, f_norm > 0 ? f_norm : 1.0,
                         {options.tolerance, options.max_iterations}, *lu, jacobian_matrix, clock);
      check_finite(problem, u, "displacement", "load increment " + std::to_string(inc));
      result.iterations += report.iterations;
      result.linear_iterations += report.iterations;
      result.residual = report.residual;
      inc_converged = report.converged;
    }
    for (int it = 0; !tangent && it <= options.max_iterations; ++it) {
      const auto p = problem.positions(u);
      result.inverted_max = std::max(result.inverted_max, count_inverted(problem, p));
      linearize(problem, rotate, p, u, result.rotations, elastic, clock);
      const Eigen::VectorXd r = f - elastic;
      check_finite(problem, r, "force",
                   "load increment " + std::to_string(inc) + ", iteration " + std::to_string(it));
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
      result.linear_iterations +=
          clock.time("solve", [&] { return solver.solve(b, du); }).iterations;
      u += du;
      ++result.iterations;
      check_finite(
          problem, u, "displacement",
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
