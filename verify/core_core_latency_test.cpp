// The cores' handoff time that records carry (core/core_latency.hpp): a positive, bounded time
// with two cores, and none when the process may use one.
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

TEST(CoreLatency, OneCoreGivesNone) {
  cpu_set_t before, one;
  ASSERT_EQ(sched_getaffinity(0, sizeof before, &before), 0);
  int first = 0;
  while (!CPU_ISSET(first, &before)) ++first;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  const double ns = measure_core_to_core_ns();
  ASSERT_EQ(sched_setaffinity(0, sizeof before, &before), 0);
  EXPECT_EQ(ns, 0.0);
}

}  // namespace
}  // namespace corofem
