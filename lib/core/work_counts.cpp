#include "core/work_counts.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif
#if defined(__linux__)
#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace corofem {

namespace {

#if defined(__linux__)
constexpr std::uint64_t cache_event(std::uint64_t cache) {
  return cache | (PERF_COUNT_HW_CACHE_OP_READ << 8) | (PERF_COUNT_HW_CACHE_RESULT_MISS << 16);
}

constexpr PerfCounters::Event kDefaultEvents[3] = {
    {PERF_TYPE_HARDWARE, PERF_COUNT_HW_INSTRUCTIONS},
    {PERF_TYPE_HW_CACHE, cache_event(PERF_COUNT_HW_CACHE_L1D)},
    {PERF_TYPE_HW_CACHE, cache_event(PERF_COUNT_HW_CACHE_LL)},
};
constexpr const char* kEventNames[3] = {"instructions", "L1-dcache-load-misses", "LLC-load-misses"};

/// One event of the group led by `leader` (-1: it leads): the group is scheduled on the PMU
/// whole, so its three counts cover the same instructions.
int open_event(const PerfCounters::Event& event, int leader) {
  perf_event_attr attr{};
  attr.size = sizeof attr;
  attr.type = event.type;
  attr.config = event.config;
  attr.exclude_kernel = 1;  // what the code does, not the system calls it makes
  attr.exclude_hv = 1;
  return static_cast<int>(
      syscall(SYS_perf_event_open, &attr, 0 /* this thread */, -1 /* any CPU */, leader, 0));
}
#endif

}  // namespace

std::string processor_seen() {
#if defined(__x86_64__) || defined(__i386__)
  unsigned regs[12] = {};
  for (unsigned i = 0; i < 3; ++i)
    if (!__get_cpuid(0x80000002 + i, &regs[4 * i], &regs[4 * i + 1], &regs[4 * i + 2],
                     &regs[4 * i + 3]))
      return "unknown";
  char brand[49] = {};
  std::memcpy(brand, regs, 48);
  std::string text(brand);
  const std::size_t first = text.find_first_not_of(' '), last = text.find_last_not_of(' ');
  return first == std::string::npos ? "unknown" : text.substr(first, last - first + 1);
#else
  return "unknown";
#endif
}

std::optional<PerfCounters> PerfCounters::open(std::string& why_not) {
#if defined(__linux__)
  return open(kDefaultEvents, why_not);
#else
  why_not = "perf events exist on Linux only";
  return std::nullopt;
#endif
}

std::optional<PerfCounters> PerfCounters::open(const Event (&events)[3], std::string& why_not) {
#if defined(__linux__)
  int fds[3] = {-1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    fds[i] = open_event(events[i], i == 0 ? -1 : fds[0]);
    if (fds[i] < 0) {
      why_not = std::string("perf_event_open(") + kEventNames[i] + "): " + std::strerror(errno) +
                " (no hardware counters here: a VM without a virtual PMU, or "
                "/proc/sys/kernel/perf_event_paranoid above 2)";
      for (int j = 0; j < i; ++j) ::close(fds[j]);
      return std::nullopt;
    }
  }
  return PerfCounters(fds);
#else
  (void)events;
  why_not = "perf events exist on Linux only";
  return std::nullopt;
#endif
}

PerfCounters::PerfCounters(const int (&fds)[3]) {
  for (int i = 0; i < 3; ++i) fds_[i] = fds[i];
}

PerfCounters::PerfCounters(PerfCounters&& other) noexcept {
  for (int i = 0; i < 3; ++i) {
    fds_[i] = other.fds_[i];
    other.fds_[i] = -1;
  }
}

PerfCounters& PerfCounters::operator=(PerfCounters&& other) noexcept {
  std::swap(fds_, other.fds_);  // other closes ours
  return *this;
}

PerfCounters::~PerfCounters() {
#if defined(__linux__)
  for (int fd : fds_)
    if (fd >= 0) ::close(fd);
#endif
}

WorkCounts PerfCounters::read() const {
  std::uint64_t values[3] = {0, 0, 0};
#if defined(__linux__)
  for (int i = 0; i < 3; ++i)
    if (::read(fds_[i], &values[i], sizeof values[i]) != sizeof values[i])
      throw std::runtime_error(std::string("reading a perf counter: ") + std::strerror(errno));
#endif
  return {values[0], values[1], values[2]};
}

}  // namespace corofem
