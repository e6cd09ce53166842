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

/// Ranks of this job on this machine: mpirun's OMPI_COMM_WORLD_LOCAL_SIZE (or MPI_LOCALNRANKS),
/// 1 outside mpirun. They multiply a run's memory per rank.
int ranks_on_this_machine();

/// Throws InputError("<what> would give about N tets, which need about X GB (<basis>) ...; this
/// machine has Y GB") when ranks_on_this_machine() x `bytes` exceeds the physical memory, before
/// anything is allocated.
void require_memory(double tets, double bytes, const std::string& what, const std::string& basis);

}  // namespace corofem
