// The event log (core/event_log.hpp), the observer a timed run reads its solver's times and counts
// from: each section's wall time by name, summed over its runs and over the threads that ran it at
// once; each event counted; each solve kept as reported; the multigrid's parts read from it.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "core/event_log.hpp"
#include "multigrid/multigrid_parts.hpp"

namespace corofem {
namespace {

using namespace std::chrono_literals;

// steady_clock never runs slow: a section that slept t lasted at least t. No upper bound is
// asserted (a shared machine may stall any thread for long).
TEST(EventLog, SectionsSumTheirRunsNestedAndOnEitherThread) {
  EventLog log;
  in_section(&log, "outer", [&] {
    in_section(&log, "inner", [] { std::this_thread::sleep_for(2ms); });
    in_section(&log, "inner", [] { std::this_thread::sleep_for(2ms); });
  });
  EXPECT_GE(log.ms("inner"), 4.0);
  EXPECT_GE(log.ms("outer"), log.ms("inner"));  // an enclosing section holds its parts' time
  EXPECT_EQ(log.ms("never"), 0.0);
  // Two threads in sections of one name at once: each closes its own, both counted.
  std::thread other([&] { in_section(&log, "side", [] { std::this_thread::sleep_for(3ms); }); });
  in_section(&log, "side", [] { std::this_thread::sleep_for(3ms); });
  other.join();
  EXPECT_GE(log.ms("side"), 6.0);
}

TEST(EventLog, ASectionEndsThroughAnException) {
  EventLog log;
  EXPECT_THROW(in_section(&log, "failing", [] { throw std::runtime_error("x"); }),
               std::runtime_error);
  in_section(&log, "after", [] { std::this_thread::sleep_for(1ms); });
  EXPECT_GE(log.ms("after"), 1.0);  // closed by itself: "failing" left nothing open
}

TEST(EventLog, EventsAreCountedAndSolvesKeptInOrder) {
  EventLog log;
  for (int k = 0; k < 3; ++k) mark_event(&log, "update");
  mark_event(&log, "factorization");
  log.solved("mgpcg", 7, 1e-5, 0.2);
  log.solved("jacobi-pcg", 90, 2e-5, 0.9);
  EXPECT_EQ(log.count("update"), 3);
  EXPECT_EQ(log.count("factorization"), 1);
  EXPECT_EQ(log.count("deferred update"), 0);
  ASSERT_EQ(log.solves().size(), 2u);
  EXPECT_EQ(log.solves()[0].solver, "mgpcg");
  EXPECT_EQ(log.solves()[0].iterations, 7);
  EXPECT_EQ(log.solves()[1].rate, 0.9);
}

TEST(EventLog, EachSolveKeepsItsOwnSolversIterations) {
  // An auto trial's candidates iterate in turn into one log: each solve takes the iterations its
  // own solver reported since that solver's last solve, and a direct solve none.
  EventLog log;
  log.iterated("mgpcg", 1, 0.1);
  log.iterated("jacobi-pcg", 1, 0.5);
  log.iterated("mgpcg", 2, 0.01);
  log.solved("mgpcg", 2, 0.01, 0.1);
  log.iterated("jacobi-pcg", 2, 0.25);
  log.solved("jacobi-pcg", 2, 0.25, 0.5);
  log.solved("cholmod", 1, 1e-15, 0);
  log.iterated("mgpcg", 1, 0.2);
  log.solved("mgpcg", 1, 0.2, 0.2);
  ASSERT_EQ(log.solves().size(), 4u);
  EXPECT_EQ(log.solves()[0].residuals, (std::vector<double>{0.1, 0.01}));
  EXPECT_EQ(log.solves()[1].residuals, (std::vector<double>{0.5, 0.25}));
  EXPECT_TRUE(log.solves()[2].residuals.empty());
  EXPECT_EQ(log.solves()[3].residuals, (std::vector<double>{0.2}));
}

TEST(EventLog, TheMultigridsPartsAreMeansOverItsOwnSolvesAndUpdates) {
  // An auto trial's log holds both candidates' solves (linalg_solver_choice_test.cpp): the
  // multigrid's parts (multigrid/multigrid_parts.hpp) are means over its own, and the update's
  // over the "update" events.
  EventLog log;
  in_section(&log, "fine_smooth", [] { std::this_thread::sleep_for(2ms); });
  in_section(&log, "galerkin", [] { std::this_thread::sleep_for(2ms); });
  mark_event(&log, "update");
  mark_event(&log, "update");
  log.solved("mgpcg", 7, 1e-5, 0.2);
  log.solved("jacobi-pcg", 90, 2e-5, 0.9);
  log.solved("jacobi-pcg", 80, 2e-5, 0.9);
  EXPECT_EQ(solve_parts_ms(log).fine_smooth, log.ms("fine_smooth"));  // one MG-PCG solve
  EXPECT_EQ(update_parts_ms(log).galerkin, log.ms("galerkin") / 2);
  EXPECT_EQ(solve_parts_ms(log).coarsest, 0.0);
}

}  // namespace
}  // namespace corofem
