#include "multigrid/multigrid_summary.hpp"

#include "core/statistics.hpp"

namespace corofem {

MultigridSummary summarize(const MultigridSolver& solver, const MultigridLog& log) {
  MultigridSummary s;
  s.params = solver.params();
  const MultigridHierarchy& hierarchy = solver.hierarchy();
  double blocks = 0;
  for (int h = 0; h < hierarchy.num_levels(); ++h) {
    const BrcMatrix& a = hierarchy.matrix(h);
    s.levels.push_back({a.block_rows, a.col_index.size()});
    blocks += static_cast<double>(a.col_index.size());
  }
  s.origins = solver.level_origins();
  s.operator_complexity = blocks / static_cast<double>(hierarchy.matrix(0).col_index.size());
  s.setup = log.setup_ms();
  s.update = log.update_parts_ms();
  s.solve = log.solve_parts_ms();
  std::vector<double> rho, iterations;
  for (const SolveStats& stats : log.solve_log()) {
    if (stats.iterations == 0) continue;  // a zero right-hand side: nothing was solved
    rho.push_back(stats.convergence_factor);
    iterations.push_back(stats.iterations);
  }
  s.solves = static_cast<int>(rho.size());
  if (!rho.empty()) {
    s.rho = median(rho);
    s.iterations = median(iterations);
  }
  s.coarsest_shifts = solver.coarsest_shifts();
  s.updates = solver.updates();
  s.coarsest_factorizations = solver.coarsest_factorizations();
  s.galerkin_refreshes = solver.galerkin_refreshes();
  s.deferred_updates = log.deferred_updates();
  s.ended_early = solver.ended_early();
  return s;
}

}  // namespace corofem
