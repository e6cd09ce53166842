#pragma once
// Memory of this process, for records of long runs and the constant-memory gate.

namespace corofem {

/// Peak resident set size so far (kB), from getrusage.
long peak_rss_kb();

/// Current resident set size (kB), from /proc/self/statm; 0 where unavailable.
long current_rss_kb();

}  // namespace corofem
