// Order statistics: the median, and the Pareto front the speed-accuracy sweeps and tune mark.
#include <gtest/gtest.h>

#include <cmath>

#include "core/statistics.hpp"

namespace corofem {
namespace {

TEST(Statistics, MedianOfOddEvenAndNone) {
  EXPECT_EQ(median({3, 1, 2}), 2);
  EXPECT_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(median({})));
}

TEST(Statistics, ParetoFrontKeepsWhatNothingBeatsInBoth) {
  // (cost, error): the staircase (1,3), (2,2), (3,1) is the front; (2,3) is beaten by (2,2) in
  // error at equal cost, (3,3) by all three; an exact duplicate of a front point stays on it.
  const std::vector<bool> front = pareto_front({{1, 3}, {2, 2}, {3, 1}, {2, 3}, {3, 3}, {2, 2}});
  EXPECT_EQ(front, (std::vector<bool>{true, true, true, false, false, true}));
  EXPECT_TRUE(pareto_front({}).empty());
}

}  // namespace
}  // namespace corofem
