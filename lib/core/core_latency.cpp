#include "core/core_latency.hpp"

#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "core/statistics.hpp"

namespace corofem {
namespace {

/// The first two cores in the calling thread's affinity mask; where it holds one (OpenMP's
/// OMP_PROC_BIND pins the initial thread to its place), the first two online cores, which the
/// pins below then try (a core outside the process's cpuset refuses the pin: the thread runs
/// unpinned).
std::vector<int> first_two_cores() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  std::vector<int> cores;
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0)
    for (int c = 0; c < CPU_SETSIZE && cores.size() < 2; ++c)
      if (CPU_ISSET(c, &allowed)) cores.push_back(c);
  if (cores.size() < 2 && std::thread::hardware_concurrency() >= 2) cores = {0, 1};
  return cores;
}

void pin_to(int core) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(core, &set);
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);  // unpinned on failure: still a time
}

}  // namespace

double measure_core_to_core_ns() {
  const std::vector<int> cores = first_two_cores();
  if (cores.size() < 2) return 0;
  constexpr int kRounds = 5, kTrips = 2000;
  // Two threads of their own, pinned: the caller's thread and the OpenMP team keep their masks.
  // The line holds the count of handoffs; each side waits for its turn, then passes the line on.
  // Where the two cannot run at once (a CPU quota below two cores), each handoff waits for a
  // time slice: the measurement stops at its deadline and gives the handoffs it timed.
  using Clock = std::chrono::steady_clock;
  alignas(64) std::atomic<long> turn{0};
  std::atomic<bool> ready{false}, stop{false};
  std::vector<double> one_way_ns;
  const auto deadline = Clock::now() + std::chrono::milliseconds(100);
  std::thread answer([&] {
    pin_to(cores[1]);
    ready.store(true, std::memory_order_release);
    for (long n = 1; n < 2L * kRounds * kTrips; n += 2) {
      while (turn.load(std::memory_order_acquire) != n)
        if (stop.load(std::memory_order_relaxed)) return;
      turn.store(n + 1, std::memory_order_release);
    }
  });
  std::thread ask([&] {
    pin_to(cores[0]);
    while (!ready.load(std::memory_order_acquire)) {
    }
    const auto wait_for = [&](long value) {  // false past the deadline
      for (unsigned spins = 1; turn.load(std::memory_order_acquire) != value; ++spins)
        if (spins % 4096 == 0 && Clock::now() > deadline) return false;
      return true;
    };
    long n = 0;
    bool in_time = true;
    for (int r = 0; r < kRounds && in_time; ++r) {
      const auto start = Clock::now();
      int trips = 0;
      for (; trips < kTrips; ++trips, n += 2) {
        turn.store(n + 1, std::memory_order_release);
        if (!(in_time = wait_for(n + 2))) break;
      }
      const std::chrono::duration<double, std::nano> took = Clock::now() - start;
      if (trips > 0) one_way_ns.push_back(took.count() / (2.0 * trips));
    }
    stop = true;
  });
  ask.join();
  answer.join();
  return one_way_ns.empty() ? 0 : median(one_way_ns);
}

}  // namespace corofem
