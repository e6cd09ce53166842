#include "multigrid/multigrid_summary.hpp"

#include "core/statistics.hpp"

namespace corofem {

MultigridSummary summarize(const MultigridSolver& solver, const EventLog& log) {
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
  s.setup = setup_parts_ms(log);
  s.update = update_parts_ms(log);
  s.solve = solve_parts_ms(log);
  std::vector<double> rho, iterations;
  for (const LoggedSolve& solve : log.solves()) {
    // A zero right-hand side: nothing was solved. Another solver's: an auto trial's candidate.
    if (solve.iterations == 0 || !is_multigrid_solve(solve)) continue;
    rho.push_back(solve.rate);
    iterations.push_back(solve.iterations);
  }
  s.solves = static_cast<int>(rho.size());
  if (!rho.empty()) {
    s.rho = median(rho);
    s.iterations = median(iterations);
  }
  s.coarsest_shifts = log.count("coarsest shift");
  s.updates = log.count("update");
  s.coarsest_factorizations = log.count("coarsest factorization");
  s.galerkin_refreshes = log.count("galerkin refresh");
  s.deferred_updates = log.count("deferred update");
  s.ended_early = solver.ended_early();
  return s;
}

}  // namespace corofem
