#pragma once
// The observer a timed run attaches to its multigrid solver (linalg/solver_observer.hpp): the
// time of each part, the counts and every solve's statistics, which the run's record reads
// (multigrid/multigrid_summary.hpp).
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "linalg/solver_observer.hpp"

namespace corofem {

/// Where a multigrid solver's time went, in ms, by part.
struct MultigridSetupParts {
  double transfers = 0;         ///< the hierarchy's transfers (hierarchy_builder.hpp)
  double galerkin_streams = 0;  ///< the Galerkin method's precomputed streams
  /// Meshing the coarse levels, before the solver existed: set by the scene that meshed them.
  std::optional<double> coarse_meshes{};
};
struct MultigridUpdateParts {
  double galerkin = 0;   ///< every coarse E = R A R^T
  double smoothers = 0;  ///< the smoothers' set-up (inverse diagonal blocks)
  double coarsest = 0;   ///< CHOLMOD's numeric factorization and its input
};
/// The update's parts by the names the records and the update's roofline use.
inline std::array<std::pair<const char*, double>, 3> named_parts(const MultigridUpdateParts& p) {
  return {{{"galerkin", p.galerkin}, {"smoothers", p.smoothers}, {"coarsest", p.coarsest}}};
}
/// A V-cycle's parts: the finest level's smoothing, residual (absent where a pre-smoothing of
/// one sweep from zero forms it in passing: it then counts in fine_smooth) and transfers
/// (restriction and prolongation); all of these on the levels between; the coarsest level's
/// triangular solves. The rest of a solve is the outer iteration (CG's product and updates).
struct MultigridSolveParts {
  double fine_smooth = 0, fine_residual = 0, fine_transfer = 0, coarse_levels = 0, coarsest = 0;
};

class MultigridLog : public SolverObserver {
 public:
  void on_part(SolverPart part, double ms) override;
  void on_event(SolverEvent event) override;
  void on_solve(const SolveStats& stats) override;

  const MultigridSetupParts& setup_ms() const { return setup_; }
  MultigridUpdateParts update_parts_ms() const;  ///< means per update
  MultigridSolveParts solve_parts_ms() const;    ///< means per solve
  int deferred_updates() const { return deferred_updates_; }
  /// Every solve's statistics, in order.
  const std::vector<SolveStats>& solve_log() const { return solves_; }

 private:
  MultigridSetupParts setup_;
  MultigridUpdateParts update_;  ///< totals over the updates
  MultigridSolveParts solve_;    ///< totals over the solves
  int updates_ = 0, deferred_updates_ = 0;
  std::vector<SolveStats> solves_;
};

}  // namespace corofem
