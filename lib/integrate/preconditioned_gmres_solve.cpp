#include "integrate/preconditioned_gmres_solve.hpp"

#include <stdexcept>
#include <utility>

#include "core/errors.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/dirichlet.hpp"
#include "linalg/flexible_gmres.hpp"

namespace corofem {

namespace {

/// Most GMRES iterations before the factorizations take the system (as PETSc's GMRES before
/// MUMPS), and the Krylov basis: at most 2 x 50 vectors (the memory estimate counts them). On the
/// symmetric part GMRES takes 6-11 iterations; on the definite stand-in 25-45, which a restart at
/// 25 would cut off (lib/docs/newton.md).
constexpr int kMaxGmresIterations = 200;
constexpr int kGmresRestart = 50;
/// GMRES's answer is taken within this factor of its tolerance: the true residual stops at its
/// rounding floor, which can lie above a target near 1e-12 (the soft cantilever of the gates at
/// Newton tolerance 1e-10, GMRES to 1e-12: 1.1e-12 to 7e-12 in 26 of 140 tangents, each then
/// refactored). An answer within 1e3 x of it leaves Newton's step as good (SparseLuSolve takes its
/// own GMRES so too).
constexpr double kFloorSlack = 1e3;

}  // namespace

std::function<void(BrcMatrix&)> corotated_stiffness_standin(const FeProblem& problem,
                                                            const std::vector<Mat3>& rotations) {
  return [&problem, &rotations, u = Eigen::VectorXd(Eigen::VectorXd::Zero(problem.num_dofs())),
          force = Eigen::VectorXd()](BrcMatrix& standin) mutable {
    // The matrix does not depend on the displacement (only the force, dropped here, does).
    assemble_corotated(problem.elements, problem.mesh, problem.assembly, rotations, u, standin,
                       force);
    apply_dirichlet_to_matrix(problem.dirichlet, standin);
  };
}

PreconditionedGmresSolve::PreconditionedGmresSolve(LinearSolver& preconditioner,
                                                   const BrcMatrix& pattern, double tolerance,
                                                   DefiniteStandIn definite)
    : preconditioner_(preconditioner),
      symmetric_(pattern),
      tolerance_(tolerance),
      definite_(std::move(definite)) {
  if (!symmetric_.pattern_symmetric())
    throw std::logic_error("PreconditionedGmresSolve: a pattern that is not symmetric");
}

PreconditionedGmresSolve::~PreconditionedGmresSolve() = default;

int PreconditionedGmresSolve::iterations() const {
  return gmres_iterations_ + fallbacks_.factored;
}

bool PreconditionedGmresSolve::gmres_on(const BrcMatrix& a, const BrcMatrix& preconditioned,
                                        const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x.setZero(b.size());
  try {
    preconditioner_.set_matrix(preconditioned);
    const SolveStats stats = flexible_gmres(
        a, b, x, [&](const Eigen::VectorXd& v, Eigen::VectorXd& z) { preconditioner_.solve(v, z); },
        {.tolerance = tolerance_, .max_iterations = kMaxGmresIterations, .restart = kGmresRestart});
    gmres_iterations_ += stats.iterations;
    return stats.residual <= kFloorSlack * tolerance_ && x.allFinite();
  } catch (const NotConverged&) {    // the preconditioner's own iterations missed
  } catch (const NumericalFault&) {  // its coarsest factorization failed: not definite
  }
  return false;
}

Eigen::VectorXd PreconditionedGmresSolve::solve(const BrcMatrix& a, const Eigen::VectorXd& b,
                                                bool symmetric) {
  Eigen::VectorXd x;
  if (gmres_on(a, symmetric ? a : symmetric_.of(a), b, x)) return x;
  if (definite_) {
    if (standin_.num_blocks() == 0) standin_ = a;
    definite_(standin_);
    ++fallbacks_.standin;
    if (gmres_on(a, standin_, b, x)) return x;
  }
  if (!factored_) factored_ = std::make_unique<SparseLuSolve>(a);
  ++fallbacks_.factored;
  return factored_->solve(a, b, symmetric);
}

}  // namespace corofem
