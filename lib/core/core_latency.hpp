#pragma once
// How far apart, in time, the two cores a two-thread run uses are: the one-way time of a cache
// line handed between them. On a VM the host decides where the vCPUs sit, and it may move them
// during a run: the same binary's two-thread step then changes by up to 1.6x while each core's
// own speed, and the STREAM triad, do not tell (lib/docs/threads.md, "Where the host puts the two
// cores"). Records carry it (io/run_context.hpp) so that two-thread timings say which placement
// they ran in, and `corofem compare` warns when its two sides ran in different ones.

namespace corofem {

/// The one-way time, in ns, of a cache line written by one thread and read by another, the two
/// pinned to the first two cores this process may use: the median of 5 rounds of 2,000 round
/// trips on one atomic (about 2-10 ms). 0 when the machine has fewer than two cores.
double measure_core_to_core_ns();

}  // namespace corofem
