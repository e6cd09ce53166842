// The comparison's statistics: the U test's exact p against enumeration of every rank
// arrangement, its normal approximation against a published value, the Hodges-Lehmann ratio on a
// hand-computed case, and on synthetic samples of known ratio: a 10% shift found, no shift not
// found more often than alpha allows, the interval covering the true ratio.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "compare/shift_test.hpp"

namespace corofem {
namespace {

/// The oracle: P(U <= u) for n against m by enumerating which of the n + m ranks belong to the
/// first sample (every subset of size n), with no shared code.
double enumerated_cdf(int n, int m, int u) {
  const int total = n + m;
  long long count = 0, below = 0;
  for (unsigned mask = 0; mask < (1u << total); ++mask) {
    if (__builtin_popcount(mask) != n) continue;
    ++count;
    // U: pairs (first, second) with the second's rank above the first's.
    int pairs = 0;
    for (int i = 0; i < total; ++i)
      if (mask >> i & 1)
        for (int j = i + 1; j < total; ++j) pairs += !(mask >> j & 1);
    below += pairs <= u;
  }
  return static_cast<double>(below) / static_cast<double>(count);
}

TEST(ShiftTest, ExactPValueMatchesEnumeratedArrangements) {
  for (const auto& [n, m] : {std::pair{3, 3}, {4, 5}, {5, 5}, {2, 7}, {6, 6}})
    for (int u = 0; u <= n * m / 2; ++u) {
      const double expected = std::min(1.0, 2 * enumerated_cdf(n, m, u));
      // Both are ratios of integers below 2^20: equal to rounding.
      EXPECT_NEAR(exact_u_p_value(u, n, m), expected, 1e-14) << n << "x" << m << " U=" << u;
    }
  // Complete separation of 5 against 5: 2 / C(10, 5).
  EXPECT_NEAR(shift_test({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10}, 0.01).p_value, 2.0 / 252, 1e-15);
}

TEST(ShiftTest, IntervalEndpointsAreTheOrderStatisticsOfThePublishedCriticalValues) {
  // The Mann-Whitney critical values, two-sided (reject where U <= c), as tabled in Hollander and
  // Wolfe (1999, Table A.6, as U) and in the common tables of the U test: the Hodges-Lehmann
  // interval at 1 - alpha is [d_(c+1), d_(nm-c)] of the nm pairwise differences (Hollander and
  // Wolfe, ch. 4.3). An off-by-one in the code's k moves each endpoint by one difference.
  struct Row {
    int n;
    double alpha;
    int critical;
  };
  for (const Row& r : {Row{5, 0.05, 2}, Row{6, 0.05, 5}, Row{7, 0.05, 8}, Row{8, 0.05, 13},
                       Row{10, 0.05, 23}, Row{20, 0.05, 127}, Row{5, 0.01, 0}, Row{8, 0.01, 7},
                       Row{10, 0.01, 16}, Row{20, 0.01, 105}}) {
    // log x_i = i, log y_j = n j + 0.5: the differences n j - i + 0.5 are every integer from
    // -(n-1) to n(n-1), plus 0.5, once each; the k-th smallest is k - n + 0.5.
    std::vector<double> x, y;
    for (int i = 0; i < r.n; ++i) {
      x.push_back(std::exp(i));
      y.push_back(std::exp(r.n * i + 0.5));
    }
    const ShiftTest t = shift_test(x, y, r.alpha);
    ASSERT_TRUE(t.exact);
    const int k = r.critical + 1, pairs = r.n * r.n;
    EXPECT_NEAR(std::log(t.ratio_low), k - r.n + 0.5, 1e-9) << r.n << " at " << r.alpha;
    EXPECT_NEAR(std::log(t.ratio_high), (pairs + 1 - k) - r.n + 0.5, 1e-9)
        << r.n << " at " << r.alpha;
  }
}

TEST(ShiftTest, TiedSamplesUseTheTieCorrectedNormalApproximation) {
  // Chromium Pinpoint's mann_whitney_u test: [0]*5 against [1]*5 gives p = 0.0039767517097886512
  // (normal approximation, tie-corrected variance, continuity correction). Times must be
  // positive, so 1 and 2 (the test is on ranks: the same p).
  const ShiftTest t = shift_test({1, 1, 1, 1, 1}, {2, 2, 2, 2, 2}, 0.01);
  EXPECT_FALSE(t.exact);
  EXPECT_NEAR(t.p_value, 0.0039767517097886512, 1e-12);
  EXPECT_DOUBLE_EQ(t.ratio, 2.0);
}

TEST(ShiftTest, HodgesLehmannRatioIsTheMedianPairwiseRatio) {
  // NEW/BASE over all 9 pairs: 2/3, 1, 4/3, 2, 2, 2, 3, 4, 6; the median is 2.
  const ShiftTest t = shift_test({1, 2, 3}, {2, 4, 6}, 0.05);
  EXPECT_NEAR(t.ratio, 2.0, 1e-12);
  // U: NEW above BASE in 7 pairs, one tie (2 against 2) counted a half.
  EXPECT_DOUBLE_EQ(t.u, 7.5);
  EXPECT_LE(t.ratio_low, t.ratio);
  EXPECT_GE(t.ratio_high, t.ratio);
}

TEST(ShiftTest, RefusesEmptyOrNonPositiveSamples) {
  EXPECT_THROW(shift_test({}, {1}, 0.01), std::invalid_argument);
  EXPECT_THROW(shift_test({1, 0}, {1}, 0.01), std::invalid_argument);
  EXPECT_THROW(shift_test({1}, {NAN}, 0.01), std::invalid_argument);
}

/// `count` times of a run, log-normal with 3% spread around `scale` (the spread of per-run
/// medians measured between alternated runs on these VMs is 1-4%).
std::vector<double> runs(std::mt19937& rng, int count, double scale) {
  std::normal_distribution<double> noise(0, 0.03);
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(scale * std::exp(noise(rng)));
  return out;
}

TEST(ShiftTest, FindsATenPercentShiftAndCoversTheTrueRatio) {
  std::mt19937 rng(20261206);
  const double alpha = 0.01;
  int found = 0, covered = 0;
  const int trials = 200;
  for (int trial = 0; trial < trials; ++trial) {
    const ShiftTest t = shift_test(runs(rng, 8, 1.0), runs(rng, 8, 1.10), alpha);
    found += t.p_value < alpha && t.ratio > 1.05;
    covered += t.ratio_low <= 1.10 && 1.10 <= t.ratio_high;
  }
  // A 10% shift is 3.2 spreads: at 8 against 8 the U test's power is above 0.95 (normal
  // approximation of its power: 0.99); the 99% interval covers at least 99% of the time (exact
  // intervals are conservative), and 200 trials leave binomial room of about 2%.
  EXPECT_GE(found, 190) << found << " of " << trials;
  EXPECT_GE(covered, 194) << covered << " of " << trials;
}

TEST(ShiftTest, NoShiftIsFoundAtMostAsOftenAsAlphaAllows) {
  std::mt19937 rng(7);
  const double alpha = 0.01;
  int significant = 0;
  const int trials = 1000;
  for (int trial = 0; trial < trials; ++trial)
    significant += shift_test(runs(rng, 8, 1.0), runs(rng, 8, 1.0), alpha).p_value < alpha;
  // Expected 10 (alpha), binomial sd 3.1: 22 is four of them above.
  EXPECT_LE(significant, 22) << significant << " of " << trials;
}

/// `count` per-run medians as these VMs give them: 3% spread, and a third of the runs in a slow
/// mode 1.5x the fast one (measured: the cantilever's solve at one thread, 0.195 or 0.29 ms).
std::vector<double> bimodal_runs(std::mt19937& rng, int count, double scale) {
  std::bernoulli_distribution slow(1.0 / 3);
  std::vector<double> out = runs(rng, count, scale);
  for (double& v : out) v *= slow(rng) ? 1.5 : 1.0;
  return out;
}

TEST(StratifiedShiftTest, OneStratumIsTheStandardizedU) {
  // van Elteren's statistic of a single stratum is U standardized by its null mean and variance
  // (no continuity correction): for 20 against 20 without ties, sd = sqrt(400 * 41 / 12).
  std::mt19937 rng(31);
  const std::vector<double> x = runs(rng, 20, 1.0), y = runs(rng, 20, 1.02);
  const ShiftTest single = shift_test(x, y, 0.01);
  const ShiftTest stratified = stratified_shift_test({{x, y}}, 0.01);
  const double z = (single.u - 200) / std::sqrt(400.0 * 41 / 12);
  EXPECT_NEAR(stratified.u, z, 1e-12);
  EXPECT_NEAR(stratified.p_value, std::erfc(std::abs(z) / std::sqrt(2.0)), 1e-12);
  EXPECT_DOUBLE_EQ(stratified.ratio, single.ratio);  // the same pairs
}

TEST(StratifiedShiftTest, EightCasesFindATenPercentShiftThatOneCaseMisses) {
  // The gate's situation: 8 cases (scenes x thread counts) of 10 runs a side, bimodal runs.
  std::mt19937 rng(37);
  int found = 0, single_found = 0, covered = 0;
  const int trials = 100;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<Stratum> strata;
    for (int c = 0; c < 8; ++c)
      strata.push_back({bimodal_runs(rng, 10, 1.0 + c), bimodal_runs(rng, 10, 1.1 * (1.0 + c))});
    const ShiftTest t = stratified_shift_test(strata, 0.01);
    // Holm over the gate's ~60 rows asks the smallest p for 0.01 / 60.
    found += t.p_value < 0.01 / 60 && t.ratio > 1.05;
    covered += t.ratio_low <= 1.1 && 1.1 <= t.ratio_high;
    single_found += shift_test(strata[0].base, strata[0].contender, 0.01).p_value < 0.01 / 60;
  }
  EXPECT_GE(found, 95) << found << " of " << trials;
  EXPECT_LE(single_found, 20) << "one case alone should rarely reach it: " << single_found;
  EXPECT_GE(covered, 95) << covered << " of " << trials;
}

TEST(StratifiedShiftTest, NoShiftIsFoundAtMostAsOftenAsAlphaAllows) {
  std::mt19937 rng(41);
  int significant = 0;
  const int trials = 500;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<Stratum> strata;
    for (int c = 0; c < 8; ++c)
      strata.push_back({bimodal_runs(rng, 10, 1.0 + c), bimodal_runs(rng, 10, 1.0 + c)});
    significant += stratified_shift_test(strata, 0.01).p_value < 0.01;
  }
  // Expected 5 (alpha), binomial sd 2.2: 14 is four of them above.
  EXPECT_LE(significant, 14) << significant << " of " << trials;
}

TEST(ShiftTest, LargeSamplesUseTheNormalApproximationConsistently) {
  std::mt19937 rng(11);
  const ShiftTest t = shift_test(runs(rng, 100, 1.0), runs(rng, 100, 1.02), 0.01);
  EXPECT_FALSE(t.exact);
  // 100 against 100 at 3% spread: the interval of a 2% shift is about +-1.1% wide.
  EXPECT_NEAR(t.ratio, 1.02, 0.01);
  EXPECT_LT(t.ratio_high - t.ratio_low, 0.04);
}

}  // namespace
}  // namespace corofem
