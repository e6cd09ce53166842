#pragma once
// What a multigrid solver measured over a run, typed: its levels, the medians of its solves and
// its time by part. The records write it (io/solver_record.hpp); the report reads its fields.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "multigrid/multigrid_parts.hpp"
#include "multigrid/multigrid_solver.hpp"

namespace corofem {

struct MultigridLevelSummary {
  int vertices = 0;
  std::size_t blocks = 0;
};

struct MultigridSummary {
  MultigridParams params;
  std::vector<MultigridLevelSummary> levels;  ///< finest first
  std::vector<CoarseLevelOrigin> origins;     ///< where level h + 1 came from, at h
  double operator_complexity = 0;             ///< blocks of all levels / blocks of the finest
  MultigridSetupParts setup;
  MultigridUpdateParts update;            ///< means per update
  MultigridSolveParts solve;              ///< means per solve
  int solves = 0;                         ///< solves of a non-zero right-hand side
  std::optional<double> rho, iterations;  ///< medians over those solves
  int coarsest_shifts = 0, deferred_updates = 0;
  /// Updates of the matrix, and those that factorized the coarsest level (the rest kept its
  /// factor).
  int updates = 0, coarsest_factorizations = 0, galerkin_refreshes = 0;
  std::string ended_early;  ///< MultigridSolver::ended_early
  /// The share of the updates that factorized the coarsest level (1 before any update).
  double refactor_share() const {
    return updates > 0 ? static_cast<double>(coarsest_factorizations) / updates : 1.0;
  }
};

/// What `solver` is (its levels, params, origins) and what `log`, its observer from its set-up
/// on, heard.
MultigridSummary summarize(const MultigridSolver& solver, const EventLog& log);

}  // namespace corofem
