#pragma once
// The "context" object every record carries: what produced it (commit, compiler, flags, machine).
#include <nlohmann/json.hpp>

namespace corofem {

/// Commit, compiler, flags, build type, CPU model, cache sizes, cores, hostname, UTC date, and at
/// two or more threads the one-way time of a cache line between the first two cores
/// (core_to_core_ns: where the host put them).
nlohmann::json run_context();

}  // namespace corofem
