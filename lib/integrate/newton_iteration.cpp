#include "integrate/newton_iteration.hpp"

#include <Eigen/UmfPackSupport>

#include "core/errors.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

struct SparseLuSolve::State {
  explicit State(const BrcMatrix& pattern) : eigen(pattern) {}
  BrcToEigen eigen;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  bool analyzed = false;
};

SparseLuSolve::SparseLuSolve(const BrcMatrix& pattern) : state_(std::make_unique<State>(pattern)) {}
SparseLuSolve::~SparseLuSolve() = default;

Eigen::VectorXd SparseLuSolve::solve(const BrcMatrix& a, const Eigen::VectorXd& b) {
  state_->eigen.update(a);
  if (!state_->analyzed) {
    state_->lu.analyzePattern(state_->eigen.matrix());
    state_->analyzed = true;
  }
  state_->lu.factorize(state_->eigen.matrix());
  if (state_->lu.info() != Eigen::Success)
    throw NumericalFault("Newton: the tangent matrix is singular");
  Eigen::VectorXd x = state_->lu.solve(b);
  if (!x.allFinite()) throw NumericalFault("Newton: the tangent solve gave non-finite values");
  return x;
}

NewtonReport newton_iterate(Eigen::VectorXd& z,
                            const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residual,
                            const std::function<void(BrcMatrix&)>& jacobian,
                            const DirichletConditions& fixed, double scale,
                            const NewtonSettings& settings, SparseLuSolve& lu, BrcMatrix& work,
                            PhaseClock& clock) {
  NewtonReport report;
  const DirichletConditions step_bc{fixed.fixed,
                                    Eigen::VectorXd::Zero(z.size())};  // dz = 0 where fixed
  Eigen::VectorXd g = residual(z);
  double norm = free_norm(fixed, g);
  for (;; ++report.iterations) {
    report.residual = norm / scale;
    if (report.residual <= settings.tolerance) {
      report.converged = true;
      return report;
    }
    if (report.iterations == settings.max_iterations) return report;
    jacobian(work);
    Eigen::VectorXd rhs = -g;
    apply_dirichlet(step_bc, work, rhs);
    const Eigen::VectorXd dz = clock.time("solve", [&] { return lu.solve(work, rhs); });
    // Safeguarded full steps: halve only when the residual would become non-finite or grow by
    // more than max_growth (see NewtonSettings).
    double alpha = 1;
    for (int halving = 0;; ++halving) {
      const Eigen::VectorXd trial = z + alpha * dz;
      Eigen::VectorXd g_trial = residual(trial);
      const double trial_norm = free_norm(fixed, g_trial);
      if ((std::isfinite(trial_norm) && trial_norm <= settings.max_growth * norm) ||
          halving == settings.max_halvings) {
        if (!std::isfinite(trial_norm))
          throw NumericalFault("Newton: the residual became non-finite");
        z = trial;
        g = std::move(g_trial);
        norm = trial_norm;
        report.halvings += halving;
        break;
      }
      alpha *= 0.5;
    }
  }
}

}  // namespace corofem
