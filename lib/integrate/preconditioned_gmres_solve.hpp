#pragma once
// Static Newton's tangent J dz = rhs by flexible GMRES preconditioned by one of corofem's own SPD
// solvers (the multigrid: MG-PCG or V-cycles) set to J's symmetric part (J + J^T) / 2. The
// corotated tangent is nearly symmetric (its skew part is the rotations' derivative), so the
// preconditioned iterations are few, and the memory is the multigrid's instead of a sparse
// factor's fill: the route to meshes a factorization does not fit.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "fem/fe_problem.hpp"
#include "integrate/newton_iteration.hpp"
#include "linalg/linear_solver.hpp"
#include "sparse/brc_matrix.hpp"
#include "sparse/brc_symmetric_part.hpp"

namespace corofem {

/// The relative residual to which a scene's multigrid, as the preconditioner, solves the
/// symmetric part (scene/scene_simulation.cpp sets it): tighter buys GMRES few iterations for
/// solves that take longer, looser costs it more (lib/docs/newton.md).
constexpr double kTangentPreconditionerTolerance = 1e-2;

/// Static Newton's definite stand-in: the corotated stiffness R K R^T of `problem` at `rotations`
/// (what the lagged iteration solves), its fixed DOFs eliminated as the tangent's are. Reads
/// `rotations` when called: pass the ones the iteration keeps current.
std::function<void(BrcMatrix&)> corotated_stiffness_standin(const FeProblem& problem,
                                                            const std::vector<Mat3>& rotations);

class PreconditionedGmresSolve : public NewtonLinearSolve {
 public:
  /// Assembles into its argument (the tangent's pattern, fixed DOFs eliminated) a positive
  /// definite matrix near the tangent's symmetric part, for the preconditioner where that part
  /// is indefinite: static Newton's is the corotated stiffness R K R^T at the iterate's rotations.
  using DefiniteStandIn = std::function<void(BrcMatrix&)>;
  /// `preconditioner` solves the symmetric part (set_matrix at every solve); `tolerance`: GMRES's
  /// relative residual. `pattern`: the tangent's (symmetric) block pattern.
  PreconditionedGmresSolve(LinearSolver& preconditioner, const BrcMatrix& pattern, double tolerance,
                           DefiniteStandIn definite = {});
  ~PreconditionedGmresSolve() override;
  /// Where GMRES misses its tolerance (by more than its rounding floor, 1e3 x) or the
  /// preconditioner fails (the symmetric part is indefinite: a body in compression, past a
  /// buckling point; the multigrid's coarsest Cholesky or its CG breaks down), GMRES again with
  /// the multigrid on the definite stand-in, where one is given; where that fails too, the sparse
  /// factorizations of SparseLuSolve take the system.
  Eigen::VectorXd solve(const BrcMatrix& a, const Eigen::VectorXd& b, bool symmetric) override;
  /// GMRES iterations, and one for each solve the factorizations took.
  int iterations() const override;
  TangentFallbacks fallbacks() const override { return fallbacks_; }

 private:
  /// GMRES on `a` from zero, preconditioned by the multigrid set to `preconditioned`; false where
  /// it misses or the multigrid fails.
  bool gmres_on(const BrcMatrix& a, const BrcMatrix& preconditioned, const Eigen::VectorXd& b,
                Eigen::VectorXd& x);

  LinearSolver& preconditioner_;
  BrcSymmetricPart symmetric_;  ///< (J + J^T) / 2, on J's pattern
  double tolerance_;
  DefiniteStandIn definite_;
  BrcMatrix standin_;  ///< the stand-in's values, made at its first use
  int gmres_iterations_ = 0;
  TangentFallbacks fallbacks_;
  std::unique_ptr<SparseLuSolve> factored_;  ///< made at the first fallback
};

}  // namespace corofem
