#include "linalg/preconditioned_cg.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "linalg/gauss_seidel.hpp"

namespace corofem {

namespace {

/// CG's vector passes run over fixed chunks of entries on the threads; a reduction sums the
/// chunks' partial sums in chunk order, so it is the same bits at every thread count.
constexpr Eigen::Index kChunk = 1024;  // a few on the threads gate's meshes too

/// sum over the chunks [lo, hi) of n of partial(lo, hi), which may also update entries of its
/// chunk.
template <class Partial>
double chunked_sum(Eigen::Index n, const Partial& partial) {
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> sums(chunks);
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (Eigen::Index c = 0; c < chunks; ++c)
    sums[c] = partial(c * kChunk, std::min(n, (c + 1) * kChunk));
  double total = 0;
  for (const double s : sums) total += s;
  return total;
}

/// Within a chunk, Eigen's vectorized reductions (several accumulators; a plain loop is one
/// chain of dependent adds, 4x slower at one thread).
double dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  return chunked_sum(u.size(), [&](Eigen::Index lo, Eigen::Index hi) {
    return u.segment(lo, hi - lo).dot(v.segment(lo, hi - lo));
  });
}

}  // namespace

SolveStats preconditioned_cg(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             const Preconditioner& precondition, double tolerance,
                             int max_iterations, const char* name,
                             const Eigen::VectorXd* initial_residual, EventObserver* events) {
  SolveStats stats;
  const double b_norm = start_iterative_solve(b, x);
  if (b_norm == 0) return stats;
  Eigen::VectorXd r, z = Eigen::VectorXd::Zero(b.size()), q;
  if (initial_residual)
    r = *initial_residual;
  else
    a.residual(b, x, r);
  const double r0 = r.norm();
  double rk = r0;
  if (rk > tolerance * b_norm) {
    precondition(r, z);
    Eigen::VectorXd p = z;
    double rz = dot(r, z);
    const Eigen::Index n = b.size();
    while (stats.iterations < max_iterations) {
      a.multiply(p, q);
      const double alpha = rz / dot(p, q);
      // x += alpha p and r -= alpha q, with |r|^2, in one pass.
      rk = std::sqrt(chunked_sum(n, [&](Eigen::Index lo, Eigen::Index hi) {
        x.segment(lo, hi - lo) += alpha * p.segment(lo, hi - lo);
        r.segment(lo, hi - lo) -= alpha * q.segment(lo, hi - lo);
        return r.segment(lo, hi - lo).squaredNorm();
      }));
      ++stats.iterations;
      if (events) events->iterated(name, stats.iterations, rk / b_norm);
      if (!std::isfinite(rk))
        throw NumericalFault(std::string(name) + ": residual became non-finite");
      if (rk <= tolerance * b_norm) break;
      precondition(r, z);
      const double rz_next = dot(r, z), beta = rz_next / rz;
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
      for (Eigen::Index i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
      rz = rz_next;
    }
  }
  stats.residual = rk / b_norm;
  stats.convergence_factor =
      stats.iterations > 0 && r0 > 0 ? std::pow(rk / r0, 1.0 / stats.iterations) : 0;
  require_converged(stats, tolerance, name, "CG iterations");
  return stats;
}

namespace {

class JacobiPcgSolver : public LinearSolver {
 public:
  JacobiPcgSolver(double tolerance, int max_iterations)
      : tolerance_(tolerance), max_iterations_(max_iterations) {}
  std::string name() const override { return "jacobi-pcg"; }
  void set_matrix(const BrcMatrix& a) override {
    a_ = a;
    diagonal_.set_matrix(a_);
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    const SolveStats stats = preconditioned_cg(
        a_, b, x,
        [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { diagonal_.block_jacobi(r, z); },
        tolerance_, max_iterations_, "jacobi-pcg", nullptr, events_);
    report_solved(stats);
    return stats;
  }

 private:
  double tolerance_;
  int max_iterations_;
  BrcMatrix a_;
  BlockGaussSeidel diagonal_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_jacobi_pcg_solver(double tolerance, int max_iterations) {
  return std::make_unique<JacobiPcgSolver>(tolerance, max_iterations);
}

}  // namespace corofem
