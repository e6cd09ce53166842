#pragma once
// Memory of this process, for records of long runs and the constant-memory gate, and the check
// that a mesh about to be built fits in this machine's memory.
#include <string>

namespace corofem {

/// Peak resident set size so far (kB), from getrusage.
long peak_rss_kb();

/// Current resident set size (kB), from /proc/self/statm; 0 where unavailable.
long current_rss_kb();

/// This machine's physical memory in bytes (sysconf); 0 where unavailable.
double physical_memory_bytes();

/// Bytes a run needs per tet, measured: a dynamic MG-PCG run of a 384,000-tet box peaks at
/// 3.37 GB (8.8 kB per tet; 48,000 tets: 6.7 kB), rounded up.
constexpr double kBytesPerTet = 10e3;

/// Throws InputError("<what> would give about N tets, which need about X GB ...; this machine has
/// Y GB") when `tets` x kBytesPerTet exceeds the physical memory, before anything is allocated.
void require_memory_for_tets(double tets, const std::string& what);

}  // namespace corofem
