#pragma once
// Damped Newton for the nonlinear systems of the corotated model, g(z) = 0 over the free DOFs:
// static equilibrium f_ext - f_int(u) = 0 and the fully implicit Euler step. Each iteration solves
// J dz = -g (a NewtonLinearSolve): J is non-symmetric for the non-conservative rotation methods and
// indefinite past a buckling point, so neither CG nor Cholesky applies in general. On one process
// (SparseLuSolve) where g is a potential's gradient J is its Hessian, factored by Cholesky while it
// is positive definite; a non-symmetric J by GMRES on its symmetric part's Cholesky factor, or a
// sparse LU (UMFPACK). With a PETSc solver (KrylovNewtonSolve) its GMRES, on one process or over
// the ranks' rows of a distributed mesh; with corofem's multigrid (static:
// PreconditionedGmresSolve) flexible GMRES preconditioned by the multigrid on J's symmetric part.
// Step lengths:
//  - where g is the gradient of a potential (the caller passes it: implicit Euler with polar
//    rotations, whose force is conservative, is then the minimization of the incremental
//    potential), a backtracking line search on that potential (Armijo) along every Newton step that
//    descends it;
//  - otherwise full Newton steps, halved only when the residual would become non-finite or grow by
//    more than max_growth: a line search on |g| (Armijo) stalls corotated problems, whose first
//    step from a straight state rotates elements linearly and stretches them (on the soft
//    cantilever of the gates the full step raises |g| 100-fold, then Newton converges in 3 more
//    iterations; with Armijo halving on |g| it took 57 iterations for the first load increment).
//  - either search starts from the step_bound the caller gives, if any (static increments: no
//    edge stretched by more than twice its rest length; the tangent is a linearization about the
//    current rotations, and a full step from the rest state under a large load inverted half the
//    bunny's tets and took Newton 225 iterations, against 9 bounded).
#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <memory>

#include "fem/dirichlet.hpp"
#include "fem/rank_view.hpp"
#include "fem/simulation_result.hpp"
#include "linalg/linear_solver.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

struct NewtonSettings {
  double tolerance = 1e-10;  ///< converged when |g|_free <= tolerance * scale
  int max_iterations = 50;
  int max_halvings = 12;    ///< smallest step 2^-12
  double max_growth = 1e4;  ///< largest accepted |g_new| / |g|
  /// Converged at the rounding floor: |g| within floor_factor x tolerance and an iteration that
  /// no longer halves it (Newton near a root would square it; rounding in f_int, whose element
  /// terms cancel, stops it there).
  double floor_factor = 100;
  /// > 0: stop, stalled, once the residual is within stall_factor x tolerance and the last
  /// stall_iterations iterations have not halved it: a floor above the tolerance (the internal
  /// forces' own error) that more iterations do not pass. 0: iterate to max_iterations.
  int stall_iterations = 0;
  double stall_factor = 1e4;
  /// The longest step length allowed along a Newton step dz, at most 1 (empty: 1).
  std::function<double(const Eigen::VectorXd& dz)> step_bound;
  /// Called after every step taken, with the iterations so far and |g|_free / scale (progress).
  std::function<void(int iteration, double residual)> on_iteration{};
};

struct NewtonReport {
  int iterations = 0;
  int halvings = 0;             ///< step halvings in all (both rules)
  int potential_steps = 0;      ///< steps along which the potential descends
  int potential_fallbacks = 0;  ///< of those, steps where the search found no decrease
  double residual = 0;          ///< |g|_free / scale at the end
  bool converged = false;
  bool at_floor = false;  ///< converged by the floor rule (see NewtonSettings::floor_factor)
  bool stalled = false;   ///< stopped by the stall rule (see NewtonSettings::stall_iterations)
};

/// A potential's value and the size of its terms before they cancel (what its rounding is
/// relative to: an incremental potential's kinetic and momentum terms nearly cancel).
struct PotentialValue {
  double value = 0;
  double magnitude = 0;
};

/// The relative residual to which an iterative solve of a Newton tangent is taken: 1e-2 x the
/// Newton tolerance (an inexact step leaves that fraction of the last residual), at least 1e-13
/// (near rounding).
inline double newton_tangent_tolerance(double newton_tolerance) {
  return std::max(1e-2 * newton_tolerance, 1e-13);
}

/// How a Newton iteration solves its linear system J dz = rhs (fixed DOFs already eliminated).
class NewtonLinearSolve {
 public:
  virtual ~NewtonLinearSolve() = default;
  /// x = A^{-1} b; `symmetric`: A is a potential's Hessian. Throws NumericalFault on failure.
  virtual Eigen::VectorXd solve(const BrcMatrix& a, const Eigen::VectorXd& b,
                                bool symmetric = false) = 0;
  /// The linear iterations of every call so far (a factorization's solve counts one).
  virtual int iterations() const = 0;
  /// The systems an iterative path handed on (none where it has no fallback).
  virtual TangentFallbacks fallbacks() const { return {}; }
};

/// The factorizations of the iteration matrices, analyzed once per pattern and refactored each
/// iteration: CHOLMOD's Cholesky for a symmetric matrix (a time step's M + dt^2 K, the Hessian of
/// a potential); a non-symmetric one (a corotated tangent) by GMRES to 1e-12 preconditioned by
/// the Cholesky factor of its symmetric part; UMFPACK's LU where either part is not positive
/// definite (a buckled body) or GMRES misses.
class SparseLuSolve : public NewtonLinearSolve {
 public:
  /// `kind`: the Cholesky factorizations' (the LU is UMFPACK's).
  explicit SparseLuSolve(const BrcMatrix& pattern, Factorization kind = Factorization::Supernodal);
  ~SparseLuSolve() override;
  /// x = A^{-1} b; throws NumericalFault when A is singular.
  Eigen::VectorXd solve(const BrcMatrix& a, const Eigen::VectorXd& b,
                        bool symmetric = false) override;
  /// false: every non-symmetric matrix by the LU (the baseline BM_NewtonTangentSolve measures).
  void set_krylov(bool enabled);
  /// How many solves each way went: Cholesky, GMRES on the symmetric part's factor, LU.
  int cholesky_solves() const;
  int krylov_solves() const;
  int lu_solves() const;
  int iterations() const override { return cholesky_solves() + krylov_solves() + lu_solves(); }

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// J dz = rhs by an iterative LinearSolver set up for J at every call, from dz = 0: PETSc's GMRES
/// (solver/petsc_solver.hpp, `nonsymmetric`); on a distributed mesh over the ranks' owned rows,
/// the halo entries of dz received from their owners.
class KrylovNewtonSolve : public NewtonLinearSolve {
 public:
  explicit KrylovNewtonSolve(LinearSolver& solver) : solver_(solver) {}
  Eigen::VectorXd solve(const BrcMatrix& a, const Eigen::VectorXd& b, bool symmetric) override;
  int iterations() const override { return iterations_; }

 private:
  LinearSolver& solver_;
  int iterations_ = 0;
};

/// Solves g(z) = 0 from `z` (fixed DOFs of `fixed` keep their values in z). `residual(z)` returns
/// g at z (and may update state such as rotations); `jacobian(z, J)` fills J at the z of the last
/// residual call; `potential`, if given, the potential whose gradient g is, at the z of the last
/// residual call. Phases "rotate"/"assemble" are the callers'; the linear solve is timed as
/// "solve". On a distributed mesh (`ranks`) |g| sums the ranks' owned rows; a potential is not
/// supported there (its value and slope would be sums over the ranks too).
NewtonReport newton_iterate(
    Eigen::VectorXd& z, const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& residual,
    const std::function<void(BrcMatrix&)>& jacobian, const DirichletConditions& fixed, double scale,
    const NewtonSettings& settings, NewtonLinearSolve& linear, BrcMatrix& work, PhaseClock& clock,
    const std::function<PotentialValue()>& potential = {}, const RankView& ranks = {});

}  // namespace corofem
