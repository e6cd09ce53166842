#pragma once
// The "context" object every record carries: what produced it (commit, compiler, flags, machine).
#include <nlohmann/json.hpp>

namespace corofem {

/// Commit, compiler, flags, build type, CPU model, cache sizes, cores, hostname, UTC date.
nlohmann::json run_context();

}  // namespace corofem
