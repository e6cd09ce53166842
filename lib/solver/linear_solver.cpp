#include "solver/linear_solver.hpp"

#include <cstdio>

#include "core/errors.hpp"

namespace corofem {

void require_converged(const SolveStats& stats, double tolerance, const std::string& solver,
                       const std::string& unit) {
  if (stats.residual <= tolerance) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "relative residual %.3g after %d %s, above the tolerance %.3g (mean reduction %.4f per "
                "iteration)",
                stats.residual, stats.iterations, unit.c_str(), tolerance, stats.convergence_factor);
  throw NotConverged(solver + ": " + text);
}

}  // namespace corofem
