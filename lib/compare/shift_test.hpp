#pragma once
// Whether two samples of a timing differ, and by what factor: the Mann-Whitney U test with the
// Hodges-Lehmann estimate of the shift and its distribution-free confidence interval, on the
// logarithms of the times, so that the shift is a ratio NEW/BASE.
//
// Why these: step times are skewed and heavy-tailed (a preempted step is 2-10x the others), so a
// test on means (Welch's t) is dominated by the outliers; the U test uses ranks only. Google
// Benchmark's tools/compare.py and Chromium's Pinpoint decide with the same test over
// repetitions. The Hodges-Lehmann estimate (the median of all pairwise differences) is the
// estimator that goes with the U test, and its interval comes from U's own null distribution
// (Bauer 1972, Hollander and Wolfe ch. 4), with no bootstrap resampling (whose median intervals
// cover badly at 5-10 samples).
#include <vector>

namespace corofem {

struct ShiftTest {
  int base_count = 0, new_count = 0;
  double u = 0;        ///< pairs (base, new) with new > base, ties counted 1/2
  double p_value = 1;  ///< two-sided
  bool exact = false;  ///< p from U's exact null distribution (else normal, tie-corrected)
  double ratio = 1;    ///< Hodges-Lehmann estimate of NEW/BASE
  double ratio_low = 0, ratio_high = 0;  ///< its (1 - alpha) confidence interval
};

/// Compares positive samples (times); `alpha` sets the interval's level. Throws
/// std::invalid_argument on an empty sample or a value that is not positive and finite.
ShiftTest shift_test(const std::vector<double>& base, const std::vector<double>& contender,
                     double alpha);

/// One stratum of a stratified comparison: the same quantity of one case (a scene at a thread
/// count), its BASE and NEW samples.
struct Stratum {
  std::vector<double> base, contender;
};

/// The same shift tested across strata at once (van Elteren 1960): each stratum's U weighted by
/// 1 / (n + m + 1), their sum standardized (normal, tie-corrected). A slowdown of one phase's code
/// shows in that phase of every case: pooled, 8 cases of 10 runs find a 10% shift that no single
/// case of these VMs' bimodal runs can. The ratio is the Hodges-Lehmann estimate over every
/// within-stratum pair; its interval inverts the test (the shifts it does not reject at alpha).
/// Throws std::invalid_argument like shift_test, or without strata.
ShiftTest stratified_shift_test(const std::vector<Stratum>& strata, double alpha);

/// Two-sided p-value of U for samples of sizes n and m without ties, from the exact null
/// distribution (the number of rank arrangements with each U).
double exact_u_p_value(double u, int n, int m);

}  // namespace corofem
