#pragma once
// The linear solver behind every step: A x = b with A symmetric positive definite in BRC form.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/event_observer.hpp"
#include "linalg/factorization_kind.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

class MultigridSolver;
struct SolverChoice;

struct SolveStats {
  int iterations = 0;             ///< V-cycles or CG iterations; 1 for a direct solve
  double residual = 0;            ///< |b - A x| / |b| reached
  double convergence_factor = 0;  ///< (r_k / r_0)^(1/k) for iterative solvers
};

/// Throws NotConverged when an iterative solve stopped at its cap above `tolerance`: a solution
/// that silently misses its accuracy would pass as a result. `solver` and `unit` name the solver
/// and its unit of work in the message ("multigrid", "V-cycles").
void require_converged(const SolveStats& stats, double tolerance, const std::string& solver,
                       const std::string& unit);

/// The start of every iterative solve: x sized like b (zero if it was not), and |b|. For b = 0
/// the solution is x = 0, set here; the caller returns at once when the returned norm is 0.
double start_iterative_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  /// Takes new values of A (the pattern stays that of the first call).
  virtual void set_matrix(const BrcMatrix& a) = 0;
  /// set_matrix for a caller that rewrites all of a's values before its next call anyway: the
  /// solver may take the values by swapping them with its own storage (a keeps its pattern; its
  /// values are then unspecified). The multigrid solver saves its copy of the fine matrix so.
  virtual void take_matrix(BrcMatrix& a) { set_matrix(a); }
  /// x holds the initial guess on entry (ignored by direct solvers).
  virtual SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// The multigrid solver this one is, or wraps, for what reads a hierarchy (the run's
  /// multigrid record, the step's roofline, the Galerkin oracle); null for every other solver.
  /// The solver says so itself: no caller casts.
  virtual const MultigridSolver* multigrid() const { return nullptr; }
  /// What a solver that chooses among others (linalg/solver_choice.hpp) measured and kept; null
  /// for every other solver.
  virtual const SolverChoice* choice() const { return nullptr; }
  /// Marks its work for `events` (kept; null stops the marks; core/event_observer.hpp): the
  /// sections of its parts (a multigrid's Galerkin products, smoothers, coarsest level, its
  /// cycle's levels), its counted events (a multigrid's updates and factorizations, CHOLMOD's
  /// "factorization") and every solve's statistics (report_solved). A solver without parts marks no
  /// sections: its work counts in the phase that called it.
  virtual void observe(EventObserver* events) { events_ = events; }

 protected:
  /// Tells the observer, where there is one, that a solve ended with `stats`.
  void report_solved(const SolveStats& stats) const {
    if (events_)
      events_->solved(name(), stats.iterations, stats.residual, stats.convergence_factor);
  }
  EventObserver* events_ = nullptr;
};

/// CHOLMOD: symbolic analysis at the first matrix, numeric refactorization at every later one.
std::unique_ptr<LinearSolver> make_cholmod_solver(Factorization kind = Factorization::Supernodal);

}  // namespace corofem
