#pragma once
// The records' entries for the numerical components: their parameters and what a multigrid
// solver measured, written from their typed structs (the numerics themselves hold no JSON).
#include <nlohmann/json.hpp>
#include <optional>

#include "linalg/solver_choice.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// A measurement that may not exist (a median over no solves): its value, or null.
nlohmann::json to_json(const std::optional<double>& value);
/// A component's settings or its description (core/parameters.hpp): an object by key.
nlohmann::json to_json(const Parameters& parameters);

nlohmann::json to_json(const HierarchyParams& params);
/// The hierarchy, transfer, Galerkin method, smoother and cycle.
nlohmann::json to_json(const MultigridParams& params);
/// A multigrid solver's time by part (ms), the parts that ran.
nlohmann::json to_json(const MultigridSetupParts& parts);
nlohmann::json to_json(const MultigridUpdateParts& parts);
nlohmann::json to_json(const MultigridSolveParts& parts);
/// Where a coarse level came from: `source`, and a mesh's size and fit or a lattice's cell.
nlohmann::json to_json(const CoarseLevelOrigin& origin);

/// The record's `multigrid`: parameters, per level vertices, blocks and origin, operator
/// complexity, setup times, the mean parts of an update and a solve, the median rho and
/// iterations over the solves so far, the coarsest level's semidefinite shifts, and how many
/// updates had their coarsest factorization run in the next solve (`deferred_updates`).
nlohmann::json to_json(const MultigridSummary& summary);

/// The record's `solver_choice` (analysis.solver "auto"): per candidate its trial solves' costs
/// (ms) and iterations, its cost (the least after the warm-up) or its failure; the rule and the
/// candidate kept (null if the run ended within the trial).
nlohmann::json to_json(const SolverChoice& choice);

}  // namespace corofem
