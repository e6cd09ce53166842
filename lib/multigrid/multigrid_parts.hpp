#pragma once
// Where a multigrid solver's time went, by part, read from the event log a timed run attaches to
// it (core/event_log.hpp): the sections it marks (multigrid/solver_part.hpp) and its events.
// The run's record writes them (multigrid/multigrid_summary.hpp).
#include <array>
#include <optional>
#include <utility>

#include "core/event_log.hpp"

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

/// The set-up's parts, totals.
MultigridSetupParts setup_parts_ms(const EventLog& log);
/// The update's parts, means per "update" event.
MultigridUpdateParts update_parts_ms(const EventLog& log);
/// A solve's parts, means per solve of a multigrid solver ("mgpcg" or "multigrid").
MultigridSolveParts solve_parts_ms(const EventLog& log);
/// Whether a logged solve is a multigrid solver's (the log may hold a trial's other candidate's).
bool is_multigrid_solve(const LoggedSolve& solve);

}  // namespace corofem
