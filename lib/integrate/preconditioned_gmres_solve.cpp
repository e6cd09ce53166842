#include "integrate/preconditioned_gmres_solve.hpp"

#include <stdexcept>

#include "core/errors.hpp"
#include "linalg/flexible_gmres.hpp"

namespace corofem {

namespace {

/// Most GMRES iterations before the factorizations take the system (as PETSc's GMRES before
/// MUMPS), and the Krylov basis: 2 x 25 vectors, the 50 the memory estimate counts.
constexpr int kMaxGmresIterations = 200;
constexpr int kGmresRestart = 25;
/// GMRES's answer is taken within this factor of its tolerance: the true residual stops at its
/// rounding floor, which can lie above a target near 1e-12 (the soft cantilever of the gates at
/// Newton tolerance 1e-10, GMRES to 1e-12: 1.1e-12 to 7e-12 in 26 of 140 tangents, each then
/// refactored). An answer within 1e3 x of it leaves Newton's step as good (SparseLuSolve takes its
/// own GMRES so too).
constexpr double kFloorSlack = 1e3;

}  // namespace

PreconditionedGmresSolve::PreconditionedGmresSolve(LinearSolver& preconditioner,
                                                   const BrcMatrix& pattern, double tolerance)
    : preconditioner_(preconditioner), symmetric_(pattern), tolerance_(tolerance) {
  if (!symmetric_.pattern_symmetric())
    throw std::logic_error("PreconditionedGmresSolve: a pattern that is not symmetric");
}

PreconditionedGmresSolve::~PreconditionedGmresSolve() = default;

int PreconditionedGmresSolve::iterations() const {
  return gmres_iterations_ + fallback_solves();
}

Eigen::VectorXd PreconditionedGmresSolve::solve(const BrcMatrix& a, const Eigen::VectorXd& b,
                                                bool symmetric) {
  const BrcMatrix& part = symmetric ? a : symmetric_.of(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  try {
    preconditioner_.set_matrix(part);
    const SolveStats stats = flexible_gmres(
        a, b, x, [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) { preconditioner_.solve(v, z); },
        {.tolerance = tolerance_, .max_iterations = kMaxGmresIterations, .restart = kGmresRestart});
    gmres_iterations_ += stats.iterations;
    if (stats.residual <= kFloorSlack * tolerance_ && x.allFinite()) return x;
  } catch (const NotConverged&) {    // the preconditioner's own iterations missed
  } catch (const NumericalFault&) {  // its coarsest factorization failed: not definite
  }
  if (!factored_) factored_ = std::make_unique<SparseLuSolve>(a);
  return factored_->solve(a, b, symmetric);
}

}  // namespace corofem
