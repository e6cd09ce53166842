#pragma once
// The run record's `phase_counts`: each phase's and each solver part's instructions, D1 and
// last-level misses (core/section_counter.hpp), and what counted them.
#include <nlohmann/json.hpp>
#include <string>

#include "core/section_counter.hpp"

namespace corofem {

/// `sections`: every section path's inclusive counts ("update" holds "update/galerkin");
/// `outside`: the stretches between the sections (the step loop, the progress lines); `source`,
/// the events' definitions, callgrind's simulated caches, the processor the code saw (under
/// valgrind its synthetic one), the marks made; `threads`: the run's
/// (perf counts the calling thread alone); callgrind's `allocator_left_out`: the C library's
/// allocator's counts, in no section (core/allocator_calls.hpp).
nlohmann::json to_json(const SectionCounter& counter, int threads);

/// A counted run that could not count: the source asked for, and why (the record then holds
/// timings only).
nlohmann::json unavailable_counts(CountSource asked, const std::string& why_not);

}  // namespace corofem
