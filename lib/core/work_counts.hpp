#pragma once
// How much work a stretch of code did, in counts that do not wobble with the machine's load:
// instructions executed, and first-level data and last-level cache misses. Read from the hardware
// by perf events in-process (PerfCounters), or simulated by valgrind's callgrind from the marks a
// counted run leaves (core/section_counter.hpp).
#include <cstdint>
#include <optional>
#include <string>

namespace corofem {

struct WorkCounts {
  std::uint64_t instructions = 0;
  std::uint64_t d1_misses =
      0;  ///< first-level data cache misses (reads; perf's L1-dcache-load-misses)
  std::uint64_t ll_misses = 0;  ///< last-level cache misses (perf's LLC-load-misses)

  WorkCounts& operator+=(const WorkCounts& o) {
    instructions += o.instructions;
    d1_misses += o.d1_misses;
    ll_misses += o.ll_misses;
    return *this;
  }
  friend WorkCounts operator-(WorkCounts a, const WorkCounts& b) {
    a.instructions -= b.instructions;
    a.d1_misses -= b.d1_misses;
    a.ll_misses -= b.ll_misses;
    return a;
  }
};

/// The processor's brand string as the CPUID instruction gives it to this process: under valgrind
/// its synthetic CPU ("Intel(R) Core(TM) i7-4910MQ" on any AVX2 host), which is what the C
/// library, BLAS and the block kernels choose their code by; so counts made under valgrind on
/// two hosts that see the same CPU here compare. "unknown" off x86.
std::string processor_seen();

/// The calling thread's instructions, L1D read misses and last-level read misses, counted by the
/// hardware through perf_event_open (user space only). Where the machine exposes no counters (a
/// VM without a virtual PMU, perf_event_paranoid above 2, a kernel without perf events), open()
/// returns nothing and says why: the caller records that, never a count of zero.
class PerfCounters {
 public:
  /// `events`: the three events' perf_event_attr (type, config) pairs; the default is
  /// instructions, L1-dcache-load-misses and LLC-load-misses. Tests pass events that cannot open.
  struct Event {
    std::uint32_t type;
    std::uint64_t config;
  };
  static std::optional<PerfCounters> open(std::string& why_not);
  static std::optional<PerfCounters> open(const Event (&events)[3], std::string& why_not);
  PerfCounters(PerfCounters&& other) noexcept;
  PerfCounters& operator=(PerfCounters&& other) noexcept;
  PerfCounters(const PerfCounters&) = delete;
  ~PerfCounters();
  /// The counts since open().
  WorkCounts read() const;

 private:
  explicit PerfCounters(const int (&fds)[3]);
  int fds_[3];
};

}  // namespace corofem
