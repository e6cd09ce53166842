#include "solver/preconditioned_cg.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "multigrid/gauss_seidel.hpp"

namespace corofem {

SolveStats preconditioned_cg(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             const Preconditioner& precondition, double tolerance,
                             int max_iterations, const char* name) {
  SolveStats stats;
  const double b_norm = start_iterative_solve(b, x);
  if (b_norm == 0) return stats;
  Eigen::VectorXd r = b - a * x, z = Eigen::VectorXd::Zero(b.size()), q;
  const double r0 = r.norm();
  double rk = r0;
  if (rk > tolerance * b_norm) {
    precondition(r, z);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    while (stats.iterations < max_iterations) {
      a.multiply(p, q);
      const double alpha = rz / p.dot(q);
      x += alpha * p;
      r -= alpha * q;
      rk = r.norm();
      ++stats.iterations;
      if (!std::isfinite(rk)) throw NumericalFault(std::string(name) + ": residual became non-finite");
      if (rk <= tolerance * b_norm) break;
      precondition(r, z);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
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
    return preconditioned_cg(
        a_, b, x, [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { diagonal_.block_jacobi(r, z); },
        tolerance_, max_iterations_, "jacobi-pcg");
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
