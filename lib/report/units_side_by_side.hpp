#pragma once
// A section's units side by side, one thread each (a stability scene and method, a model-accuracy
// case): a small mesh's run does not use two cores, two runs do. Each unit's result is its own, so
// the section is the same at any thread count; its progress lines stay whole.
#include <functional>
#include <ostream>

namespace corofem {

/// Runs body(k, progress) for every k in [0, count) on `workers` threads, each at thread count 1,
/// from the last k down: callers list their units smallest first (the report's scenes are), so
/// the largest start first and the small ones fill the cores at the end. `progress` is a stream
/// onto `out` that writes whole lines (nullptr without `out`). The first unit's exception (in k's
/// order) is rethrown once every unit has ended.
void run_units_side_by_side(int count, int workers, std::ostream* out,
                            const std::function<void(int unit, std::ostream* progress)>& body);

}  // namespace corofem
