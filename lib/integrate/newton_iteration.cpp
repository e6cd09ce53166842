#include "integrate/newton_iteration.hpp"

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <limits>
#include <memory>

#include "core/errors.hpp"
#include "linalg/blas_turn.hpp"
#include "linalg/cholmod_factorization.hpp"
#include "linalg/flexible_gmres.hpp"
#include "sparse/brc_symmetric_part.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

namespace {

/// A non-symmetric tangent solved to this relative residual by GMRES is as good as the LU's
/// solution for Newton (whose tolerance is 1e-8 on g).
constexpr double kKrylovTolerance = 1e-12;
constexpr int kKrylovIterations = 40;

}  // namespace

struct SparseLuSolve::State {
  State(const BrcMatrix& pattern, Factorization kind)
      : eigen(pattern), cholesky(kind), symmetric_part(kind) {}
  BrcToEigen eigen;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  CholmodFactorization cholesky, symmetric_part;
  bool lu_analyzed = false, cholesky_analyzed = false, symmetric_part_analyzed = false;
  int cholesky_solves = 0, krylov_solves = 0, lu_solves = 0;
  bool krylov = true;
  /// (A + A^T) / 2 on A's pattern, and as CHOLMOD reads it: made at the first non-symmetric
  /// solve (a time step's Newton, whose matrices are symmetric, never needs them).
  struct SymmetricPart {
    explicit SymmetricPart(const BrcMatrix& pattern) : part(pattern), eigen(pattern) {}
    BrcSymmetricPart part;
    BrcToEigen eigen;
  };
  std::unique_ptr<SymmetricPart> symmetric;

  /// A non-symmetric A by GMRES, preconditioned by the Cholesky factor of its symmetric part
  /// (A + A^T) / 2: a corotated tangent is nearly symmetric (the rotations' derivative is its
  /// skew part), and a Cholesky factor with a dozen GMRES iterations costs less than the LU.
  /// False where the symmetric part is not positive definite or GMRES misses the tolerance: the
  /// LU then. The factor is not kept over a step's Newton iterations: stale, it doubled GMRES's
  /// iterations.
  bool solve_by_symmetric_part(const BrcMatrix& brc, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    if (!symmetric) symmetric = std::make_unique<SymmetricPart>(brc);
    if (!symmetric->part.pattern_symmetric()) return false;
    symmetric->eigen.update(symmetric->part.of(brc));
    const Eigen::SparseMatrix<double>& s = symmetric->eigen.matrix();
    if (!symmetric_part_analyzed) {
      symmetric_part.analyze(s);
      symmetric_part_analyzed = true;
    }
    try {
      symmetric_part.factorize(s);
    } catch (const std::runtime_error&) {
      return false;
    }
    x = Eigen::VectorXd::Zero(b.size());
    const SolveStats stats = flexible_gmres(
        brc, b, x,
        [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = symmetric_part.solve(v); },
        {.tolerance = kKrylovTolerance,
         .max_iterations = kKrylovIterations,
         .restart = kKrylovIterations});
    return x.allFinite() && stats.residual <= 1e3 * kKrylovTolerance;
  }
};

SparseLuSolve::SparseLuSolve(const BrcMatrix& pattern, Factorization kind)
    : state_(std::make_unique<State>(pattern, kind)) {}
SparseLuSolve::~SparseLuSolve() = default;
void SparseLuSolve::set_krylov(bool enabled) {
  state_->krylov = enabled;
}
int SparseLuSolve::cholesky_solves() const {
  return state_->cholesky_solves;
}
int SparseLuSolve::krylov_solves() const {
  return state_->krylov_solves;
}
int SparseLuSolve::lu_solves() const {
  return state_->lu_solves;
}

Eigen::VectorXd SparseLuSolve::solve(const BrcMatrix& a, const Eigen::VectorXd& b, bool symmetric) {
  state_->eigen.update(a);
  Eigen::VectorXd x;
  bool solved = false;
  if (symmetric) {
    if (!state_->cholesky_analyzed) {
      state_->cholesky.analyze(state_->eigen.matrix());
      state_->cholesky_analyzed = true;
    }
    try {
      state_->cholesky.factorize(state_->eigen.matrix());
      x = state_->cholesky.solve(b);
      solved = true;
      ++state_->cholesky_solves;
    } catch (const std::runtime_error&) {  // not positive definite: the LU below
    }
  }
  if (!solved && !symmetric && state_->krylov &&
      (solved = state_->solve_by_symmetric_part(a, b, x)))
    ++state_->krylov_solves;
  if (!solved) {
    ++state_->lu_solves;
    const auto turn = take_blas_turn();  // UMFPACK's dense kernels are BLAS
    if (!state_->lu_analyzed) {
      state_->lu.analyzePattern(state_->eigen.matrix());
      state_->lu_analyzed = true;
    }
    state_->lu.factorize(state_->eigen.matrix());
    if (state_->lu.info() != Eigen::Success)
      throw NumericalFault("Newton: the tangent matrix is singular");
    x = state_->lu.solve(b);
  }
  if (!x.allFinite()) throw NumericalFault("Newton: the tangent solve gave non-finite values");
  return x;
}

namespace {

/// Armijo's sufficient decrease: phi(z + alpha dz) <= phi(z) + kArmijo alpha g.dz.
constexpr double kArmijo = 1e-4;
/// The smallest decrease of the potential, relative to its terms' size, that its rounding resolves:
/// a Newton step whose predicted decrease g.dz is smaller (the last iterations, residual near 1e-8)
/// is judged by the residual (the search would halve it on rounding noise).
constexpr double kPotentialResolution = 1e-10;

}  // namespace

Eigen::VectorXd KrylovNewtonSolve::solve(const BrcMatrix& a, const Eigen::VectorXd& b, bool) {
  solver_.set_matrix(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  iterations_ += solver_.solve(b, x).iterations;
  return x;
}

namespace {

/// The stopping rules, checked before each iteration: converged; at the floor (near the
/// tolerance and no longer halving the residual); stalled (near it, and no halving for
/// stall_iterations); out of iterations.
class StoppingRules {
 public:
  explicit StoppingRules(const NewtonSettings& settings) : settings_(settings) {}
  bool stop(NewtonReport& report, double norm) {
    if (report.residual <= settings_.tolerance) return report.converged = true;
    if (report.residual <= settings_.floor_factor * settings_.tolerance &&
        norm > 0.5 * previous_norm_)
      return report.converged = report.at_floor = true;
    previous_norm_ = norm;
    if (norm <= 0.5 * last_halved_) {
      last_halved_ = norm;
      halved_at_ = report.iterations;
    }
    if (settings_.stall_iterations > 0 &&
        report.residual <= settings_.stall_factor * settings_.tolerance &&
        report.iterations - halved_at_ >= settings_.stall_iterations)
      return report.stalled = true;
    return report.iterations == settings_.max_iterations;
  }

 private:
  const NewtonSettings& settings_;
  double previous_norm_ = std::numeric_limits<double>::infinity();
  double last_halved_ = std::numeric_limits<double>::infinity();  // the stall rule's reference
  int halved_at_ = 0;
};

/// A state Newton may move to: z, its residual g and norm, its potential.
struct NewtonState {
  Eigen::VectorXd z, g;
  double norm = 0;
  PotentialValue phi{};
};

}  // namespace

NewtonReport newton_iterate(
    Eigen::VectorXd& z, const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residual,
    const std::function<void(BrcMatrix&)>& jacobian, const DirichletConditions& fixed, double scale,
    const NewtonSettings& settings, NewtonLinearSolve& linear, BrcMatrix& work, PhaseClock& clock,
    const std::function<PotentialValue()>& potential, const RankView& ranks) {
  if (potential && ranks.distributed())
    throw NumericalFault("Newton: a potential's line search does not run on a distributed mesh");
  NewtonReport report;
  const DirichletConditions step_bc{fixed.fixed,
                                    Eigen::VectorXd::Zero(z.size())};  // dz = 0 where fixed
  Eigen::VectorXd g = residual(z);
  double norm = ranks.free_norm(fixed, g);
  PotentialValue phi = potential ? potential() : PotentialValue{};
  StoppingRules rules(settings);
  for (;; ++report.iterations) {
    report.residual = norm / scale;
    if (settings.on_iteration && report.iterations > 0)
      settings.on_iteration(report.iterations, report.residual);
    if (rules.stop(report, norm)) return report;
    jacobian(work);
    Eigen::VectorXd rhs = -g;
    apply_dirichlet(step_bc, work, rhs);
    // The Jacobian of a potential's gradient is its Hessian: symmetric.
    const Eigen::VectorXd dz =
        clock.time("solve", [&] { return linear.solve(work, rhs, static_cast<bool>(potential)); });
    // The potential's slope along dz (dz is zero on the fixed DOFs): the line search on the
    // potential where dz descends it; the safeguarded full step where it does not (an indefinite
    // J), where the search finds no decrease (the potential has kinks where elements invert), or
    // without a potential.
    const double slope = g.dot(dz);
    NewtonState trial;
    const auto evaluate = [&](double alpha) {
      trial.z = z + alpha * dz;
      trial.g = residual(trial.z);
      trial.norm = ranks.free_norm(fixed, trial.g);
      trial.phi = potential ? potential() : PotentialValue{};
    };
    int halvings = 0;
    bool found = false;
    const double longest = settings.step_bound ? std::min(1.0, settings.step_bound(dz)) : 1.0;
    if (potential && slope < -kPotentialResolution * phi.magnitude) {  // Armijo on the potential
      ++report.potential_steps;
      double alpha = longest;
      for (int h = 0; h <= settings.max_halvings && !found; ++h, alpha *= 0.5) {
        evaluate(alpha);
        found = std::isfinite(trial.phi.value) &&
                trial.phi.value <= phi.value + kArmijo * alpha * slope;
        halvings += !found;
      }
      report.potential_fallbacks += !found;
    }
    if (!found) {  // the safeguarded full step
      double alpha = longest;
      for (int h = 0;; ++h, alpha *= 0.5) {
        evaluate(alpha);
        if ((std::isfinite(trial.norm) && trial.norm <= settings.max_growth * norm) ||
            h == settings.max_halvings)
          break;
        ++halvings;
      }
    }
    if (!std::isfinite(trial.norm)) throw NumericalFault("Newton: the residual became non-finite");
    z = std::move(trial.z);
    g = std::move(trial.g);
    norm = trial.norm;
    phi = trial.phi;
    report.halvings += halvings;
  }
}

}  // namespace corofem
