// A run's progress lines: a static run's on a log, each tenth of the increments and every cut,
// and no iteration lines while they come faster than one in a few seconds; on a terminal, one
// line redrawn in place that ends when the last increment converges, or, for static and dynamic
// runs alike, before anything else is written when the run stops early.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/static_progress.hpp"
#include "cli/step_progress.hpp"

namespace corofem {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// `increments` increments of 3 iterations each; the second is first cut once.
void run(StaticProgress& progress, long long increments) {
  for (long long k = 1; k <= increments; ++k) {
    for (int it = 1; it <= 3; ++it)
      progress.iteration_done(
          {.increment = k, .increments = increments, .iteration = it, .residual = 1e-3 / it});
    if (k == 2)
      progress.iteration_done({.increment = k,
                               .increments = increments,
                               .iteration = 3,
                               .residual = 3e-4,
                               .cut = true});
    progress.iteration_done({.increment = k,
                             .increments = increments,
                             .iteration = 3,
                             .residual = 1e-9,
                             .converged = true});
  }
}

TEST(StaticProgress, ALogGetsEachTenthOfTheIncrementsAndEveryCut) {
  std::ostringstream out;
  StaticProgress progress(&out, false, 1e-8);
  run(progress, 20);
  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 11u) << out.str();  // increments 2, 4, ..., 20, and the cut
  EXPECT_EQ(lines[0],
            "corofem: load increment 2 of 20 missed the tolerance after 3 iterations, residual "
            "0.0003 (to 1e-08): halved");
  EXPECT_EQ(lines[1], "corofem: load increment 2 of 20 converged in 3 iterations");
  EXPECT_EQ(lines.back(), "corofem: load increment 20 of 20 converged in 3 iterations");
}

TEST(StaticProgress, ATerminalGetsOneLineRedrawnThatEndsWithTheLastIncrement) {
  std::ostringstream out;
  StaticProgress progress(&out, true, 1e-8);
  run(progress, 3);
  const std::string text = out.str();
  // Redraws start with a carriage return; lines end only after the cut and the last increment.
  EXPECT_EQ(text.front(), '\r');
  ASSERT_EQ(lines_of(text).size(), 2u) << text;
  EXPECT_NE(lines_of(text)[0].find("missed the tolerance"), std::string::npos);
  EXPECT_NE(text.find("\rcorofem: load increment 3 of 3 converged in 3 iterations\x1b[K\n"),
            std::string::npos);
  EXPECT_EQ(text.back(), '\n');
}

TEST(StaticProgress, ALineLeftOpenByARunThatStopsEarlyIsEndedOnce) {
  std::ostringstream out;
  {
    StaticProgress progress(&out, true, 1e-8);
    progress.iteration_done(
        {.increment = 1, .increments = 3, .iteration = 3, .residual = 1e-9, .converged = true});
    EXPECT_NE(out.str().back(), '\n');  // increment 1 of 3: the line stays open for the next
    progress.end_line();
    EXPECT_EQ(out.str().back(), '\n');
    progress.end_line();
  }
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

TEST(StepProgress, ALineLeftOpenIsEndedWhenTheRunUnwinds) {
  // A dynamic run that throws at step 1 of 10: the bar's line ends before the error is written.
  std::ostringstream out;
  {
    StepProgress progress(&out, true, 10);
    std::this_thread::sleep_for(std::chrono::milliseconds(250));  // past the redraw interval
    progress.step_done(1);
    EXPECT_NE(out.str().find("step 1/10"), std::string::npos);
    EXPECT_NE(out.str().back(), '\n');
  }
  EXPECT_EQ(out.str().back(), '\n');
}

}  // namespace
}  // namespace corofem
