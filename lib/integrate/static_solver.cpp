#include "integrate/static_solver.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "fem/edge_stretch.hpp"
#include "fem/rotation_tangent.hpp"
#include "integrate/newton_iteration.hpp"
#include "integrate/preconditioned_gmres_solve.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {

namespace {

/// The most times a run halves a Newton increment that did not converge.
constexpr int kMaxIncrementCuts = 8;

/// The most a Newton step may stretch any tet edge, relative to its rest length: a longer step
/// is shortened to this along its direction. The tangent linearizes about the current rotations;
/// a step far past that folds elements over. Newton iterations (energy-newton, the whole load in
/// one increment), unbounded / bounded at 1, 1.5 and 2: the bunny's 11k tets under 400, 1000 and
/// 4000 N at its top 225 / 9 / 10 / 9, 341 / 11 / 12 / 10 and failed / 39 / 49 / 41; the horse
/// under 100 N over 150 s / 29 / 14 / 34; the soft cantilever at 3, 10 and 30 g 12 / 24 / 133 /
/// 12, 139 / 186 / 31 / 140 and 387 / 21 / 22 / 18; the quadruped scene 154 / 119 / 115 / 154.
/// At 2 no scene took more iterations than unbounded.
constexpr double kMaxEdgeStretch = 2.0;

/// Iterations without halving the residual, within 1e4 x the tolerance, after which a Newton
/// increment has stalled at the internal forces' own error (an iterative rotation method's
/// tolerance leaves a floor in the residual that more iterations and cuts do not go below:
/// lib/docs/newton.md).
constexpr int kStallIterations = 10;

/// How a load increment's iterations ended.
enum class IncrementEnd { Converged, Missed, Stalled };

/// One load increment's Newton iterations on g(u) = f_int(u) - f with the consistent tangent,
/// from `u` (its fixed DOFs set to the scaled prescribed values first). Counts into `result`.
IncrementEnd newton_increment(FeProblem& problem, RotationExtractor& rotate,
                              const RotationTangent& tangent, NewtonLinearSolve& linear,
                              BrcMatrix& jacobian_matrix, double scale, const Eigen::VectorXd& f,
                              double f_norm, const StaticOptions& options, StaticIteration& at,
                              Eigen::VectorXd& u, SimulationResult& result, PhaseClock& clock) {
  for (int i = 0; i < u.size(); ++i)
    if (problem.dirichlet.fixed[i]) u[i] = scale * problem.dirichlet.value[i];
  const int linear_before = linear.iterations();
  std::vector<Vec3> positions;
  const auto residual = [&](const Eigen::VectorXd& z) {
    positions = problem.positions(z);
    clock.time("rotate", [&] { rotate.extract(positions, result.rotations); });
    return Eigen::VectorXd(internal_forces(problem, result.rotations, z) - f);
  };
  const auto jacobian = [&](BrcMatrix& j) {
    clock.time("assemble", [&] { tangent.assemble(positions, result.rotations, j); });
  };
  const NewtonReport report = newton_iterate(
      u, residual, jacobian, problem.dirichlet, f_norm > 0 ? f_norm : 1.0,
      // The static residual is the user's criterion: no floor rule; a stall ends the increment.
      {.tolerance = options.tolerance,
       .max_iterations = options.max_iterations,
       .floor_factor = 1,
       .stall_iterations = kStallIterations,
       .step_bound =
           [&](const Eigen::VectorXd& dz) {
             const double stretch = options.ranks.max(largest_edge_stretch(problem.mesh, dz));
             return stretch > kMaxEdgeStretch ? kMaxEdgeStretch / stretch : 1.0;
           },
       .on_iteration = options.on_iteration
                           ? std::function<void(int, double)>([&](int it, double r) {
                               at.iteration = it;
                               at.residual = r;
                               options.on_iteration(at);
                             })
                           : nullptr},
      linear, jacobian_matrix, clock, {}, options.ranks);
  check_finite(problem, u, "displacement", at.name());
  at.iteration = report.iterations;
  at.residual = report.residual;
  result.iterations += report.iterations;
  result.linear_iterations += linear.iterations() - linear_before;
  result.residual = report.residual;
  return report.converged ? IncrementEnd::Converged
         : report.stalled ? IncrementEnd::Stalled
                          : IncrementEnd::Missed;
}

/// One load increment of the lagged-rotation iteration: extract the rotations at x + u, solve
/// Ktilde du = f - f_int(u), until the residual is below the tolerance (a linear problem: one
/// solve). Counts into `result`.
IncrementEnd lagged_increment(FeProblem& problem, RotationExtractor& rotate, LinearSolver& solver,
                              double scale, const Eigen::VectorXd& f, double f_norm,
                              const StaticOptions& options, StaticIteration& at, Eigen::VectorXd& u,
                              SimulationResult& result, PhaseClock& clock) {
  Eigen::VectorXd elastic, du = Eigen::VectorXd::Zero(problem.num_dofs());
  for (int it = 0; it <= options.max_iterations; ++it) {
    const auto p = problem.positions(u);
    linearize(problem, rotate, p, u, result.rotations, elastic, clock);
    const Eigen::VectorXd r = f - elastic;
    check_finite(problem, r, "force", at.name() + ", iteration " + std::to_string(it));
    result.residual = options.ranks.free_norm(problem.dirichlet, r) / (f_norm > 0 ? f_norm : 1);
    at.iteration = it;
    at.residual = result.residual;
    if (options.on_iteration && it > 0) options.on_iteration(at);
    // A linear solve is exact after one step; corotated steps iterate the lagged rotations.
    if (it > 0 && (!options.corotational || result.residual < options.tolerance))
      return IncrementEnd::Converged;
    if (it == options.max_iterations) return IncrementEnd::Missed;
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
    check_finite(problem, u, "displacement", at.name() + ", iteration " + std::to_string(it + 1));
  }
  return IncrementEnd::Missed;
}

/// Static Newton's solve of its tangent, as options.tangent_solve says.
std::unique_ptr<NewtonLinearSolve> newton_linear_solve(FeProblem& problem, LinearSolver& solver,
                                                       const StaticOptions& options,
                                                       const std::vector<Mat3>& rotations) {
  if (options.tangent_solve == TangentSolve::BySolver)
    return std::make_unique<KrylovNewtonSolve>(solver);
  if (options.ranks.distributed())  // a part's own solve would solve the part alone
    throw std::logic_error("static Newton on a distributed mesh with a serial tangent solve");
  if (options.tangent_solve == TangentSolve::PreconditionedBySolver)
    // Where the tangent's symmetric part is indefinite (a body in compression), the multigrid
    // takes the corotated stiffness R K R^T at the iterate's rotations: positive definite, and
    // GMRES's iterations stay few enough that no factor's fill is needed.
    return std::make_unique<PreconditionedGmresSolve>(
        solver, problem.stiffness, newton_tangent_tolerance(options.tolerance),
        corotated_stiffness_standin(problem, rotations));
  return std::make_unique<SparseLuSolve>(problem.stiffness, options.factorization);
}

/// Why a run stopped short of its load: stalled at a floor, or out of iterations.
std::string static_failure_message(IncrementEnd end, const StaticIteration& at,
                                   const SimulationResult& result, const StaticOptions& options) {
  const std::string cuts =
      result.increment_cuts > 0 ? ", after " + std::to_string(result.increment_cuts) + " cuts" : "";
  if (end == IncrementEnd::Stalled)
    return at.name() + " stalls at residual " + general_number(result.residual) +
           " above tolerance " + general_number(options.tolerance) + " (" +
           std::to_string(at.iteration) + " iterations" + cuts +
           "): the floor of the internal forces' own error, their rounding and an "
           "iterative rotation method's tolerance (rotation_params); a looser tolerance ends here";
  return at.name() + " did not reach tolerance " + general_number(options.tolerance) + " in " +
         std::to_string(options.max_iterations) + " iterations (residual " +
         general_number(result.residual) + cuts + ")";
}

}  // namespace

SimulationResult solve_static(FeProblem& problem, RotationExtractor& extractor,
                              LinearSolver& solver, const StaticOptions& options) {
  SimulationResult result;
  PhaseClock clock(result.timings_ms, options.sections);
  IdentityExtractor small_strain;
  RotationExtractor& rotate = options.corotational ? extractor : small_strain;
  Eigen::VectorXd& u = result.displacement;
  u = Eigen::VectorXd::Zero(problem.num_dofs());
  result.rotations.assign(problem.mesh.tets.size(), Mat3::Identity());
  result.converged = true;
  std::unique_ptr<RotationTangent> tangent;
  std::unique_ptr<NewtonLinearSolve> linear;
  BrcMatrix jacobian_matrix;
  if (options.newton && options.corotational) {
    tangent = std::make_unique<RotationTangent>(problem, rotate.method());
    linear = newton_linear_solve(problem, solver, options, result.rotations);
    jacobian_matrix = problem.stiffness;
  }
  // The load fraction reached is done / denominator, in integers, so that uncut the k-th
  // increment's scale is exactly k / load_steps. A Newton increment that does not converge (full
  // Newton steps from far away can diverge) is retried from the last converged state at half
  // the size, at most kMaxIncrementCuts times in a run.
  long long done = 0, denominator = options.corotational ? options.load_steps : 1;
  Eigen::VectorXd converged_u = u;
  std::vector<Mat3> converged_rotations = result.rotations;
  while (done < denominator) {
    const double scale = static_cast<double>(done + 1) / static_cast<double>(denominator);
    const Eigen::VectorXd f = scale * problem.external_force;
    const double f_norm = options.ranks.free_norm(problem.dirichlet, f);
    StaticIteration at{.increment = done + 1, .increments = denominator};
    const IncrementEnd end =
        tangent ? newton_increment(problem, rotate, *tangent, *linear, jacobian_matrix, scale, f,
                                   f_norm, options, at, u, result, clock)
                : lagged_increment(problem, rotate, solver, scale, f, f_norm, options, at, u,
                                   result, clock);
    // Inverted tets are counted in the states the run reaches (each increment's answer, or where
    // it stops), not in Newton's trial states on the way, nor in a cut increment's.
    const auto note_inverted = [&] {
      result.inverted_max = std::max(result.inverted_max,
                                     options.ranks.count_inverted(problem, problem.positions(u)));
    };
    if (end == IncrementEnd::Converged) {
      note_inverted();
      at.converged = true;
      if (options.on_iteration) options.on_iteration(at);
      ++done;
      ++result.steps;
      if (tangent) {  // the state a cut increment restarts from (only Newton increments are cut)
        converged_u = u;
        converged_rotations = result.rotations;
      }
      continue;
    }
    // A stalled increment is not cut: a smaller one stalls at the same relative floor.
    if (tangent && end == IncrementEnd::Missed && result.increment_cuts < kMaxIncrementCuts) {
      at.cut = true;
      if (options.on_iteration) options.on_iteration(at);
      u = converged_u;
      result.rotations = converged_rotations;
      done *= 2;
      denominator *= 2;
      ++result.increment_cuts;
      continue;
    }
    note_inverted();
    result.converged = false;
    result.message = static_failure_message(end, at, result, options);
    break;
  }
  if (linear) result.tangent_fallbacks = linear->fallbacks();
  return result;
}

}  // namespace corofem
