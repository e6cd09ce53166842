#include "integrate/newton_iteration.hpp"

#include <Eigen/UmfPackSupport>
#include <limits>

#include "core/errors.hpp"
#include "linalg/cholmod_factorization.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

struct SparseLuSolve::State {
  explicit State(const BrcMatrix& pattern) : eigen(pattern) {}
  BrcToEigen eigen;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  CholmodFactorization cholesky;
  bool lu_analyzed = false, cholesky_analyzed = false;
};

SparseLuSolve::SparseLuSolve(const BrcMatrix& pattern) : state_(std::make_unique<State>(pattern)) {}
SparseLuSolve::~SparseLuSolve() = default;

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
    } catch (const std::runtime_error&) {  // not positive definite: the LU below
    }
  }
  if (!solved) {
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

NewtonReport newton_iterate(Eigen::VectorXd& z,
                            const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residual,
                            const std::function<void(BrcMatrix&)>& jacobian,
                            const DirichletConditions& fixed, double scale,
                            const NewtonSettings& settings, SparseLuSolve& lu, BrcMatrix& work,
                            PhaseClock& clock, const std::function<PotentialValue()>& potential) {
  NewtonReport report;
  const DirichletConditions step_bc{fixed.fixed,
                                    Eigen::VectorXd::Zero(z.size())};  // dz = 0 where fixed
  Eigen::VectorXd g = residual(z);
  double norm = free_norm(fixed, g);
  PotentialValue phi = potential ? potential() : PotentialValue{};
  double previous_norm = std::numeric_limits<double>::infinity();
  for (;; ++report.iterations) {
    report.residual = norm / scale;
    if (report.residual <= settings.tolerance) {
      report.converged = true;
      return report;
    }
    if (report.residual <= settings.floor_factor * settings.tolerance &&
        norm > 0.5 * previous_norm) {
      report.converged = report.at_floor = true;
      return report;
    }
    previous_norm = norm;
    if (report.iterations == settings.max_iterations) return report;
    jacobian(work);
    Eigen::VectorXd rhs = -g;
    apply_dirichlet(step_bc, work, rhs);
    // The Jacobian of a potential's gradient is its Hessian: symmetric.
    const Eigen::VectorXd dz =
        clock.time("solve", [&] { return lu.solve(work, rhs, static_cast<bool>(potential)); });
    // The potential's slope along dz (dz is zero on the fixed DOFs): the line search on the
    // potential where dz descends it; the safeguarded full step where it does not (an indefinite
    // J), where the search finds no decrease (the potential has kinks where elements invert), or
    // without a potential.
    const double slope = g.dot(dz);
    Eigen::VectorXd trial, g_trial;
    double trial_norm = 0;
    PotentialValue trial_phi;
    const auto evaluate = [&](double alpha) {
      trial = z + alpha * dz;
      g_trial = residual(trial);
      trial_norm = free_norm(fixed, g_trial);
      trial_phi = potential ? potential() : PotentialValue{};
    };
    int halvings = 0;
    bool found = false;
    if (potential && slope < -kPotentialResolution * phi.magnitude) {  // Armijo on the potential
      ++report.potential_steps;
      double alpha = 1;
      for (int h = 0; h <= settings.max_halvings && !found; ++h, alpha *= 0.5) {
        evaluate(alpha);
        found = std::isfinite(trial_phi.value) &&
                trial_phi.value <= phi.value + kArmijo * alpha * slope;
        halvings += !found;
      }
      report.potential_fallbacks += !found;
    }
    if (!found) {  // the safeguarded full step
      double alpha = 1;
      for (int h = 0;; ++h, alpha *= 0.5) {
        evaluate(alpha);
        if ((std::isfinite(trial_norm) && trial_norm <= settings.max_growth * norm) ||
            h == settings.max_halvings)
          break;
        ++halvings;
      }
    }
    if (!std::isfinite(trial_norm)) throw NumericalFault("Newton: the residual became non-finite");
    z = std::move(trial);
    g = std::move(g_trial);
    norm = trial_norm;
    phi = trial_phi;
    report.halvings += halvings;
  }
}

}  // namespace corofem
