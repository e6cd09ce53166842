// A static run's progress lines: on a log, each tenth of the increments and every cut, and no
// iteration lines while they come faster than one in a few seconds; on a terminal, one line
// redrawn in place that ends when the last increment converges.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli/static_progress.hpp"

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

}  // namespace
}  // namespace corofem
