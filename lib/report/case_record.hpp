#pragma once
// One case of the report (a table row, a sweep point, a stability run): a failure is a result to
// record, not a reason to abort the report.
#include <functional>
#include <nlohmann/json.hpp>

namespace corofem {

/// Runs `f` and returns its record with "completed": true; if it throws, `base` with
/// "completed": false and "error": the message (kind: input, numerical, not_converged or internal).
nlohmann::json record_case(nlohmann::json base, const std::function<nlohmann::json()>& f);

/// JSON number, or null for NaN/inf (JSON has no NaN).
nlohmann::json finite_or_null(double value);

}  // namespace corofem
