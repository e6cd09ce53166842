#include "integrate/implicit_euler.hpp"

#include <chrono>
#include <memory>
#include <optional>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/threads.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "fem/rotation_tangent.hpp"
#include "linalg/projected_start.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {

namespace {

/// M scaled by `factor` added to the diagonal blocks of `a`.
void add_lumped_mass(const FeProblem& problem, double factor, BrcMatrix& a) {
  for (int v = 0; v < problem.mesh.num_vertices(); ++v) {
    auto block = a.block(problem.assembly.diagonal[v]);
    for (int c = 0; c < 3; ++c) block(c, c) += factor * problem.mass[3 * v + c];
  }
}

/// What the Newton steps keep from step to step: the tangent's rest data, the LU, a matrix.
struct NewtonStepper {
  NewtonStepper(const FeProblem& problem, RotationMethod method, Factorization kind)
      : tangent(problem, method), lu(problem.stiffness, kind), jacobian(problem.stiffness) {}
  RotationTangent tangent;
  SparseLuSolve lu;
  BrcMatrix jacobian;
};

/// Newton's start: the linearly implicit step's v' (the paper's; rotation-aware through
/// Ktilde_n), solved with the same factorizations. From v itself, a prescribed turn of the
/// supports (bar-twist: 75 degrees in the smoke run's first step) sends Newton off to residuals
/// of 1e300.
Eigen::VectorXd predictor(FeProblem& problem, NewtonStepper& newton, const DynamicOptions& options,
                          const DirichletConditions& bc, const Eigen::VectorXd& momentum,
                          const Eigen::VectorXd& internal_start, PhaseClock& clock) {
  const double dt = options.dt;
  const double mass_factor = 1 + dt * options.rayleigh_alpha, damping = dt * options.rayleigh_beta;
  Eigen::VectorXd b;
  clock.time("forces", [&] { b = momentum + dt * (problem.external_force - internal_start); });
  clock.time("system", [&] {
    const std::vector<double>& k = problem.stiffness.values;
    for (std::size_t i = 0; i < k.size(); ++i)
      newton.jacobian.values[i] = (damping + dt * dt) * k[i];
    add_lumped_mass(problem, mass_factor, newton.jacobian);
    apply_dirichlet(bc, newton.jacobian, b);
  });
  // M + (dt^2 + dt beta) Ktilde_n: symmetric positive definite.
  return clock.time("solve", [&] { return newton.lu.solve(newton.jacobian, b, true); });
}

/// One fully implicit Euler step: v' from g(v') = 0 (see the header), starting from the
/// linearly implicit step's v'. `internal_start` is the elastic force at the step's start. Where
/// the force has a potential, g is the gradient of the incremental potential
///   Phi(v') = 1/2 v'^T ((1 + dt alpha) M + dt beta K_n) v' - v'^T (M v + dt f) + E(u + dt v'),
/// which Newton's line search then lowers (newton_iteration.hpp).
SolveStats newton_step(FeProblem& problem, RotationExtractor& rotate, NewtonStepper& newton,
                       const DynamicOptions& options, int step, const DirichletConditions& bc,
                       const Eigen::VectorXd& internal_start, SimulationResult& result,
                       Eigen::VectorXd& velocity, PhaseClock& clock) {
  const double dt = options.dt;
  const double mass_factor = 1 + dt * options.rayleigh_alpha, damping = dt * options.rayleigh_beta;
  const Eigen::VectorXd momentum = problem.mass.cwiseProduct(velocity);
  std::vector<Mat3> rotations = result.rotations;
  std::vector<Vec3> positions;
  Eigen::VectorXd u1, v_last, kv;  // of the last residual call, for the potential
  const auto residual = [&](const Eigen::VectorXd& v1) {
    u1 = result.displacement + dt * v1;
    v_last = v1;
    positions = problem.positions(u1);
    clock.time("rotate", [&] { rotate.extract(positions, rotations); });
    Eigen::VectorXd g;
    clock.time("forces", [&] {
      g = mass_factor * problem.mass.cwiseProduct(v1) - momentum -
          dt * (problem.external_force - internal_forces(problem, rotations, u1));
      if (damping != 0) {
        problem.stiffness.multiply(v1, kv);
        g += damping * kv;
      }
    });
    return g;
  };
  std::function<PotentialValue()> potential;
  if (force_has_potential(rotate.method()))
    potential = [&] {
      return clock.time("forces", [&] {
        const double kinetic = 0.5 * mass_factor * v_last.dot(problem.mass.cwiseProduct(v_last));
        const double work = v_last.dot(momentum + dt * problem.external_force);
        const double elastic = elastic_energy(problem.elements, problem.mesh, rotations, u1);
        const double damped = damping != 0 ? 0.5 * damping * v_last.dot(kv) : 0.0;
        return PotentialValue{kinetic + damped - work + elastic,
                              kinetic + std::abs(damped) + std::abs(work) + std::abs(elastic)};
      });
    };
  const auto jacobian = [&](BrcMatrix& j) {
    clock.time("assemble", [&] { newton.tangent.assemble(positions, rotations, j); });
    clock.time("system", [&] { euler_newton_matrix(problem, dt, damping, mass_factor, j); });
  };
  Eigen::VectorXd v1 = predictor(problem, newton, options, bc, momentum, internal_start, clock);
  // |g| is measured against the size of its terms: the momenta before and after (the predictor's;
  // a step driven only by moving supports has nothing else) and the forces at the step's start.
  const double scale = std::max(
      free_norm(bc, momentum) + mass_factor * free_norm(bc, problem.mass.cwiseProduct(v1)) +
          dt * (free_norm(bc, problem.external_force) + free_norm(bc, internal_start)),
      1e-300);
  const NewtonReport report =
      newton_iterate(v1, residual, jacobian, bc, scale, options.newton_settings, newton.lu,
                     newton.jacobian, clock, potential);
  result.newton_halvings += report.halvings;
  result.newton_at_floor += report.at_floor;
  result.potential_fallbacks += report.potential_fallbacks;
  if (!report.converged)
    throw NotConverged("step " + std::to_string(step) + " (dt " + general_number(dt) +
                       "): Newton did not reach " +
                       general_number(options.newton_settings.tolerance) + " in " +
                       std::to_string(report.iterations) + " iterations (residual " +
                       general_number(report.residual) + ")");
  velocity = v1;
  result.rotations = rotations;
  return {report.iterations + 1, report.residual, 0.0};  // the predictor's solve counts
}

/// Counts the state's inverted elements into result.inverted_max: by the rotations' pass where it
/// counted them, else by a pass of its own.
/// Distributed (`ranks`), the whole body's count, over every rank's owned tets.
void note_inverted(const FeProblem& problem, const RotationExtractor& rotate,
                   const std::vector<Vec3>& positions, SimulationResult& result, PhaseClock& clock,
                   const RankView& ranks = {}) {
  clock.time("checks", [&] {
    const int counted = ranks.distributed() ? -1 : rotate.stats().inverted;
    result.inverted_max = std::max(
        result.inverted_max, counted >= 0 ? counted : ranks.count_inverted(problem, positions));
  });
}

/// Advances the state (result.displacement, `velocity`, result.rotations) by one fully implicit
/// Euler step of options.dt, the fixed DOFs moving to `end`. `linearized`: problem.stiffness
/// and `elastic` are already those of the state (else linearize() makes them). A step whose Newton
/// iteration fails (no convergence, a singular tangent, a non-finite residual) is cut: the state
/// is restored and the step taken as two of dt/2, the supports moving halfway in the first, at
/// most `cuts_left` halvings deep; a cut is not the rotation method failing, and it is counted.
/// newton_step leaves the state untouched when it throws, so a cut restores nothing.
SolveStats advance_by_newton(FeProblem& problem, RotationExtractor& rotate, NewtonStepper& newton,
                             DynamicOptions options, int step, const Eigen::VectorXd& end,
                             bool linearized, int cuts_left, Eigen::VectorXd& elastic,
                             SimulationResult& result, Eigen::VectorXd& velocity,
                             PhaseClock& clock) {
  if (!linearized) {
    std::vector<Vec3> p;
    clock.time("rotate", [&] { p = problem.positions(result.displacement); });
    linearize(problem, rotate, p, result.displacement, result.rotations, elastic, clock);
    note_inverted(problem, rotate, p, result, clock);
  }
  DirichletConditions bc = problem.dirichlet;  // on the velocity: reach the prescribed u
  for (int i = 0; i < problem.num_dofs(); ++i)
    bc.value[i] = bc.fixed[i] ? (end[i] - result.displacement[i]) / options.dt : 0.0;
  try {
    const SolveStats stats =
        newton_step(problem, rotate, newton, options, step, bc, elastic, result, velocity, clock);
    result.displacement += options.dt * velocity;
    return stats;
  } catch (const NotConverged&) {
    if (cuts_left == 0) throw;
  } catch (const NumericalFault&) {
    if (cuts_left == 0) throw;
  }
  ++result.step_cuts;  // problem.stiffness and `elastic` are still the step start's
  options.dt /= 2;
  const Eigen::VectorXd halfway =
      result.displacement + 0.5 * (end - result.displacement);  // read on the fixed DOFs only
  const SolveStats first = advance_by_newton(problem, rotate, newton, options, step, halfway, true,
                                             cuts_left - 1, elastic, result, velocity, clock);
  const SolveStats second = advance_by_newton(problem, rotate, newton, options, step, end, false,
                                              cuts_left - 1, elastic, result, velocity, clock);
  return {first.iterations + second.iterations, second.residual, 0.0};
}

/// The linearly implicit step's system A = (1 + dt alpha) M + (dt beta + dt^2) Ktilde (M lumped
/// on the diagonal blocks), its right-hand side, and v_{n-1}, from which the solve's start is
/// extrapolated.
/// Small strain (`constant`): Ktilde = K does not depend on the state, so K is assembled once into
/// problem.stiffness, and A is formed and handed to the solver (its multigrid update or its
/// factorization) only at the first step and when the supported DOFs change.
struct LinearStep {
  BrcMatrix system;  ///< the step's matrix; its pattern is allocated once
  Eigen::VectorXd b, previous_velocity;
  double k_scale;
  Eigen::VectorXd mass_diagonal;
  bool assemble_into_system;  ///< the assembly writes all of A, unless Ktilde itself is wanted
  bool constant;              ///< small strain: K assembled once, A formed when the supports change
  std::vector<char> solver_supports{};   ///< constant: the fixed DOFs of the A the solver holds
  Eigen::VectorXd lifted{}, k_lifted{};  ///< constant: dt u + k_scale w and K times it
  /// The start projected on the last velocities (DynamicOptions::start_history), and its result.
  std::optional<ProjectedStart> projection{};
  Eigen::VectorXd projected{};
};

/// The small-strain step's right-hand side in one product with K (K constant): f_int(u) = K u,
/// and apply_dirichlet's lift of the prescribed velocities w (the fixed DOFs' values; A's entries
/// off the diagonal are k_scale K's, M being diagonal) folded in:
///   b_free = (M v + dt f - K (dt u + k_scale w))_free,  b_fixed = w.
void small_strain_rhs(const FeProblem& problem, const DirichletConditions& bc,
                      const Eigen::VectorXd& displacement, const Eigen::VectorXd& velocity,
                      double dt, LinearStep& s) {
  s.lifted = dt * displacement;
  for (int d = 0; d < problem.num_dofs(); ++d)
    if (bc.fixed[d]) s.lifted[d] += s.k_scale * bc.value[d];
  problem.stiffness.multiply(s.lifted, s.k_lifted);
  s.b = problem.mass.cwiseProduct(velocity) + dt * problem.external_force - s.k_lifted;
  for (int d = 0; d < problem.num_dofs(); ++d)
    if (bc.fixed[d]) s.b[d] = bc.value[d];
}

/// The linearly implicit step's solve of A v' = s.b, A the matrix the solver holds.
/// `projected`: s.projected holds the start projected on the last velocities.
SolveStats solve_from_extrapolation(LinearSolver& solver, LinearStep& s, Eigen::VectorXd& velocity,
                                    PhaseClock& clock, bool projected = false) {
  return clock.time("solve", [&] {
    // The iterative solvers start from 2 v_n - v_{n-1}, the velocity extrapolated linearly
    // (v_n at the first step), or from the projection; they stop at the same
    // |b - A v| <= tolerance |b|, so only their iteration count changes (it falls: a better
    // start).
    if (projected) {
      s.previous_velocity.swap(velocity);  // v_n kept
      velocity.swap(s.projected);
    } else {
      s.previous_velocity = 2 * velocity - s.previous_velocity;  // coefficient-wise: no aliasing
      velocity.swap(s.previous_velocity);                        // the start, and v_n kept
    }
    return solver.solve(s.b, velocity);
  });
}

/// The linearly implicit step's solve for the new velocity, after the assembly:
/// A v' = M v + dt (f - f_int(u)).
SolveStats linear_implicit_solve(FeProblem& problem, LinearSolver& solver,
                                 const DynamicOptions& options, int step,
                                 const DirichletConditions& bc, const Eigen::VectorXd& elastic,
                                 const Eigen::VectorXd& displacement, LinearStep& s,
                                 Eigen::VectorXd& velocity, PhaseClock& clock) {
  const double dt = options.dt;
  // Every pass of the step is in a named phase: "forces" (the right-hand side; the elastic
  // force came out of the assembly, or, small strain, out of one product with K) and "system"
  // (A and its supports) besides rotate, assemble, update and solve.
  clock.time("forces", [&] {
    if (s.constant)
      small_strain_rhs(problem, bc, displacement, velocity, dt, s);
    else
      s.b = problem.mass.cwiseProduct(velocity) + dt * (problem.external_force - elastic);
  });
  clock.time("checks",
             [&] { check_finite(problem, s.b, "force", "step " + std::to_string(step)); });
  // Small strain: A changes with the supports only. On a distributed mesh a rank sees its own
  // part's supports, and handing the solver a matrix is collective: a change on one rank is a
  // change on all (else one rank waits in the update while the others solve).
  if (s.constant && options.ranks.sum(bc.fixed == s.solver_supports ? 0.0 : 1.0) == 0)
    return solve_from_extrapolation(solver, s, velocity, clock);
  clock.time("system", [&] {
    if (!s.assemble_into_system) {  // the scaled copy: one pass over Ktilde into A, then M
      const std::vector<double>& k = problem.stiffness.values;
      const std::ptrdiff_t values = static_cast<std::ptrdiff_t>(k.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(values / 9, LoopItems::Blocks))
      for (std::ptrdiff_t i = 0; i < values; ++i) s.system.values[i] = s.k_scale * k[i];
      add_lumped_mass(problem, 1 + dt * options.rayleigh_alpha, s.system);
    }
    if (s.constant) {  // b is lifted already
      apply_dirichlet_to_matrix(bc, s.system);
      s.solver_supports = bc.fixed;
    } else {
      apply_dirichlet(bc, s.system, s.b);
    }
  });
  // The projection needs A's products: before the solver may take its values.
  bool projected = false;
  if (s.projection)
    clock.time("solve",
               [&] { projected = s.projection->compute(s.system, s.b, velocity, s.projected); });
  // "update": multigrid hierarchy update, or CHOLMOD's numeric refactorization. A is rebuilt for
  // every call (the solver may take its values by swap).
  clock.time("update", [&] { solver.take_matrix(s.system); });
  return solve_from_extrapolation(solver, s, velocity, clock, projected);
}

/// Each phase's time in one step (the totals after it less those before), and the whole step's.
std::map<std::string, double> step_phases(const std::map<std::string, double>& before,
                                          const std::map<std::string, double>& after,
                                          std::chrono::steady_clock::time_point step_start) {
  std::map<std::string, double> phase_ms;
  for (const auto& [phase, total] : after)
    phase_ms[phase] = total - (before.count(phase) ? before.at(phase) : 0.0);
  phase_ms["step"] =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - step_start)
          .count();
  return phase_ms;
}

/// The equilibrium residual of the run's final state, |f_ext - f_int| / |f_ext| on the free
/// DOFs: how far from static rest the run ended. Extracts the final rotations into `result`.
double final_equilibrium_residual(FeProblem& problem, RotationExtractor& rotate,
                                  const DynamicOptions& options, SimulationResult& result,
                                  PhaseClock& clock) {
  clock.time("rotate",
             [&] { rotate.extract(problem.positions(result.displacement), result.rotations); });
  const Eigen::VectorXd r =
      problem.external_force - internal_forces(problem, result.rotations, result.displacement);
  check_finite(problem, r, "force", "the end of step " + std::to_string(options.steps));
  const double f_norm = options.ranks.free_norm(problem.dirichlet, problem.external_force);
  return options.ranks.free_norm(problem.dirichlet, r) / (f_norm > 0 ? f_norm : 1);
}

}  // namespace

void euler_newton_matrix(const FeProblem& problem, double dt, double damping, double mass_factor,
                         BrcMatrix& j) {
  const std::vector<double>& k = problem.stiffness.values;
  for (std::size_t i = 0; i < k.size(); ++i) j.values[i] = dt * dt * j.values[i] + damping * k[i];
  add_lumped_mass(problem, mass_factor, j);
}

SimulationResult solve_dynamic(FeProblem& problem, RotationExtractor& extractor,
                               LinearSolver& solver, const DynamicOptions& options,
                               const std::function<void(const StepState&)>& on_step) {
  SimulationResult result;
  PhaseClock clock(result.timings_ms, options.sections);
  IdentityExtractor small_strain;
  RotationExtractor& rotate = options.corotational ? extractor : small_strain;
  const int n = problem.num_dofs();
  const double dt = options.dt;
  result.displacement = Eigen::VectorXd::Zero(n);
  result.rotations.assign(problem.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(n), elastic;
  const bool small_strain_linear = !options.corotational && !options.newton;
  LinearStep linear{problem.stiffness,
                    {},
                    velocity,
                    dt * options.rayleigh_beta + dt * dt,
                    (1 + dt * options.rayleigh_alpha) * problem.mass,
                    !options.newton && !options.keep_stiffness && !small_strain_linear,
                    small_strain_linear};
  if (options.newton && options.ranks.distributed())
    throw InputError("fully implicit Euler (Newton) does not run on a distributed mesh");
  if (options.start_history > 0 && !options.newton && !linear.constant) {
    if (options.ranks.distributed())
      throw InputError("a projected start does not run on a distributed mesh");
    linear.projection.emplace(options.start_history);
  }
  std::unique_ptr<NewtonStepper> newton;
  if (options.newton)
    newton = std::make_unique<NewtonStepper>(problem, rotate.method(), options.factorization);
  for (int step = 1; step <= options.steps; ++step) {
    const auto step_start = std::chrono::steady_clock::now();
    const std::map<std::string, double> before = result.timings_ms;
    if (options.before_step) options.before_step(step, problem);
    std::vector<Vec3> p;  // the rotations' input
    clock.time("rotate", [&] { p = problem.positions(result.displacement); });
    // A = (1 + dt alpha) M + (dt beta + dt^2) Ktilde, with M lumped on the diagonal blocks: the
    // assembly writes all of it into A's values unless Ktilde itself is wanted. Small strain,
    // K once.
    if (!linear.constant || step == 1)
      linearize(problem, rotate, p, result.displacement, result.rotations, elastic, clock,
                linear.assemble_into_system
                    ? AssemblyTarget{&linear.system, linear.k_scale, &linear.mass_diagonal}
                    : AssemblyTarget{});
    note_inverted(problem, rotate, p, result, clock, options.ranks);
    SolveStats stats;
    if (options.newton) {
      stats = advance_by_newton(problem, rotate, *newton, options, step, problem.dirichlet.value,
                                true, options.max_step_cuts, elastic, result, velocity, clock);
    } else {
      DirichletConditions bc = problem.dirichlet;  // on the velocity: reach the prescribed u
      clock.time("system", [&] {
        for (int i = 0; i < n; ++i)
          bc.value[i] =
              bc.fixed[i] ? (problem.dirichlet.value[i] - result.displacement[i]) / dt : 0.0;
      });
      stats = linear_implicit_solve(problem, solver, options, step, bc, elastic,
                                    result.displacement, linear, velocity, clock);
      result.displacement += dt * velocity;
    }
    result.linear_iterations += stats.iterations;
    result.last_solve_residual = stats.residual;
    clock.time("checks", [&] {
      check_finite(problem, result.displacement, "displacement", "step " + std::to_string(step));
    });
    result.steps = step;
    if (on_step)
      on_step({step, result.displacement, velocity, result.rotations,
               step_phases(before, result.timings_ms, step_start), stats});
  }
  result.residual = final_equilibrium_residual(problem, rotate, options, result, clock);
  result.iterations = options.steps;
  result.converged = true;
  return result;
}

}  // namespace corofem
