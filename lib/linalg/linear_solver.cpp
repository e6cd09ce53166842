#include "linalg/linear_solver.hpp"

#include <cstdio>

#include "core/errors.hpp"

namespace corofem {

void require_converged(const SolveStats& stats, double tolerance, const std::string& solver,
                       const std::string& unit) {
  if (stats.residual <= tolerance) return;
  char text[256];
  std::snprintf(
      text, sizeof text,
      "relative residual %.3g after %d %s, above the tolerance %.3g (mean reduction %.4f per "
      "iteration)",
      stats.residual, stats.iterations, unit.c_str(), tolerance, stats.convergence_factor);
  throw NotConverged(solver + ": " + text);
}

double start_iterative_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (x.size() != b.size()) x.setZero(b.size());
  const double b_norm = b.norm();
  if (b_norm == 0) x.setZero();
  return b_norm;
}

}  // namespace corofem
