#include "fem/implicit_euler.hpp"

#include <chrono>

#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {

SimulationResult solve_dynamic(FeProblem& problem, RotationExtractor& extractor,
                               LinearSolver& solver, const DynamicOptions& options,
                               const std::function<void(const StepState&)>& on_step) {
  SimulationResult result;
  PhaseClock clock(result.timings_ms);
  IdentityExtractor small_strain;
  RotationExtractor& rotate = options.corotational ? extractor : small_strain;
  const int n = problem.num_dofs();
  const double dt = options.dt;
  result.displacement = Eigen::VectorXd::Zero(n);
  result.rotations.assign(problem.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(n), f0, b;
  BrcMatrix system = problem.stiffness;  // the step's matrix; its pattern is allocated once
  for (int step = 1; step <= options.steps; ++step) {
    const auto step_start = std::chrono::steady_clock::now();
    const std::map<std::string, double> before = result.timings_ms;
    if (options.before_step) options.before_step(step, problem);
    DirichletConditions bc = problem.dirichlet;  // on the velocity: reach the prescribed u
    for (int i = 0; i < n; ++i)
      bc.value[i] = bc.fixed[i] ? (problem.dirichlet.value[i] - result.displacement[i]) / dt : 0.0;
    const auto p = problem.positions(result.displacement);
    clock.time("checks", [&] { result.inverted_max = std::max(result.inverted_max, count_inverted(problem, p)); });
    linearize(problem, rotate, p, result.rotations, f0, clock);
    // Every pass of the step is in a named phase: "forces" (the right-hand side) and "system"
    // (A and its supports) besides rotate, assemble, update and solve.
    clock.time("forces", [&] {
      b = problem.mass.cwiseProduct(velocity) +
          dt * (problem.external_force -
                internal_forces(problem.elements, problem.mesh, result.rotations, result.displacement));
    });
    clock.time("checks", [&] { check_finite(problem, b, "force", "step " + std::to_string(step)); });
    clock.time("system", [&] {
      // A = (1 + dt alpha) M + (dt beta + dt^2) Ktilde, with M lumped on the diagonal blocks; the
      // scaled copy is one pass over Ktilde into the preallocated A.
      const double k_scale = dt * options.rayleigh_beta + dt * dt;
      const std::vector<double>& k = problem.stiffness.values;
      for (std::size_t i = 0; i < k.size(); ++i) system.values[i] = k_scale * k[i];
      for (int v = 0; v < problem.mesh.num_vertices(); ++v) {
        auto block = system.block(problem.assembly.diagonal[v]);
        for (int c = 0; c < 3; ++c) block(c, c) += (1 + dt * options.rayleigh_alpha) * problem.mass[3 * v + c];
      }
      apply_dirichlet(bc, system, b);
    });
    // "update": multigrid hierarchy update, or CHOLMOD's numeric refactorization.
    clock.time("update", [&] { solver.set_matrix(system); });
    const SolveStats stats = clock.time("solve", [&] { return solver.solve(b, velocity); });
    result.linear_iterations += stats.iterations;
    result.displacement += dt * velocity;
    clock.time("checks", [&] {
      check_finite(problem, result.displacement, "displacement", "step " + std::to_string(step));
    });
    result.steps = step;
    if (on_step) {
      std::map<std::string, double> phase_ms;
      for (const auto& [phase, total] : result.timings_ms)
        phase_ms[phase] = total - (before.count(phase) ? before.at(phase) : 0.0);
      phase_ms["step"] = std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - step_start)
                             .count();
      on_step({step, result.displacement, velocity, result.rotations, phase_ms, stats});
    }
  }
  // Equilibrium residual of the final state (how far from static rest the run ended).
  clock.time("rotate",
             [&] { rotate.extract(problem.positions(result.displacement), result.rotations); });
  const Eigen::VectorXd r =
      problem.external_force -
      internal_forces(problem.elements, problem.mesh, result.rotations, result.displacement);
  check_finite(problem, r, "force", "the end of step " + std::to_string(options.steps));
  const double f_norm = free_norm(problem.dirichlet, problem.external_force);
  result.residual = free_norm(problem.dirichlet, r) / (f_norm > 0 ? f_norm : 1);
  result.iterations = options.steps;
  result.converged = true;
  return result;
}

}  // namespace corofem
