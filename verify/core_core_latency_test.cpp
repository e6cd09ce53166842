// The cores' handoff time that records carry (core/core_latency.hpp): a positive, bounded time
// with two cores, also where the caller is pinned to one.
#include <gtest/gtest.h>
#include <sched.h>

#include <thread>

#include "core/core_latency.hpp"

namespace corofem {
namespace {

TEST(CoreLatency, TwoCoresHandOffALineInABoundedTime) {
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  if (CPU_COUNT(&allowed) < 2) GTEST_SKIP() << "this process may use one core";
  const double ns = measure_core_to_core_ns();
  // A handoff is at least a cache line's trip between two cores (tens of ns on any machine, not
  // under 1) and, with both running, far below a scheduler's time slice (milliseconds).
  EXPECT_GT(ns, 1.0);
  EXPECT_LT(ns, 1e6);
}

TEST(CoreLatency, ACallerPinnedToOneCoreStillMeasuresAndKeepsItsMask) {
  // OMP_PROC_BIND pins the initial thread to one core; the two cores of a two-thread run are
  // still apart, and the measurement's own pinned threads leave the caller's mask as it was.
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "this machine has one core";
  cpu_set_t before, one, after;
  ASSERT_EQ(sched_getaffinity(0, sizeof before, &before), 0);
  int first = 0;
  while (!CPU_ISSET(first, &before)) ++first;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  const double ns = measure_core_to_core_ns();
  ASSERT_EQ(sched_getaffinity(0, sizeof after, &after), 0);
  ASSERT_EQ(sched_setaffinity(0, sizeof before, &before), 0);
  EXPECT_TRUE(CPU_EQUAL(&after, &one));
  EXPECT_GT(ns, 1.0);
  EXPECT_LT(ns, 1e6);
}

}  // namespace
}  // namespace corofem
