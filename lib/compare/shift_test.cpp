#include "compare/shift_test.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace corofem {
namespace {

/// Counts of the rank arrangements of n and m values with U = 0 .. nm: the coefficients of the
/// Gaussian binomial [n+m choose n](q) = prod_{i=1..n} (1 - q^(m+i)) / (1 - q^i). Exact in long
/// double while C(n+m, n) < 2^64 (n + m <= 60; the callers keep to that).
std::vector<long double> u_counts(int n, int m) {
  const int top = n * m;
  std::vector<long double> c(top + 1, 0.0L);
  c[0] = 1;
  for (int i = 1; i <= n; ++i) {
    for (int k = top; k >= m + i; --k) c[k] -= c[k - (m + i)];  // times (1 - q^(m+i))
    for (int k = i; k <= top; ++k) c[k] += c[k - i];            // over (1 - q^i)
  }
  return c;
}

/// P(U <= k) under the null for every k, exact.
std::vector<double> exact_cdf(int n, int m) {
  const std::vector<long double> c = u_counts(n, m);
  long double total = 0;
  for (long double v : c) total += v;
  std::vector<double> cdf(c.size());
  long double sum = 0;
  for (std::size_t k = 0; k < c.size(); ++k) cdf[k] = static_cast<double>((sum += c[k]) / total);
  return cdf;
}

bool exact_applies(int n, int m, bool ties) {
  return !ties && n + m <= 60;
}

/// z with P(Z > z) = tail, by bisection on erfc (tail in (0, 0.5]).
double upper_normal_quantile(double tail) {
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::sqrt(2.0)) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> logs(const std::vector<double>& values) {
  if (values.empty()) throw std::invalid_argument("shift_test: an empty sample");
  std::vector<double> out;
  for (double v : values) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument("shift_test: a time that is not positive and finite");
    out.push_back(std::log(v));
  }
  return out;
}

/// Sum over values tied within the pooled sample of t^3 - t (the variance's tie correction).
double tie_sum_of(std::vector<double> all) {
  std::sort(all.begin(), all.end());
  double sum = 0;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j] == all[i]) ++j;
    const double tied = static_cast<double>(j - i);
    sum += tied * tied * tied - tied;
    i = j;
  }
  return sum;
}

/// A stratum in logs, with its weight and null variance of U (tie-corrected).
struct LogStratum {
  std::vector<double> x, y;
  double weight = 0, variance = 0;
};

/// van Elteren's standardized statistic with NEW shifted down by `shift` (in logs).
double stratified_z(const std::vector<LogStratum>& strata, double shift) {
  double t = 0, mean = 0, variance = 0;
  for (const LogStratum& s : strata) {
    double u = 0;
    for (double yj : s.y)
      for (double xi : s.x) u += yj - shift > xi ? 1.0 : yj - shift == xi ? 0.5 : 0.0;
    const double nm = static_cast<double>(s.x.size() * s.y.size());
    t += s.weight * u;
    mean += s.weight * nm / 2;
    variance += s.weight * s.weight * s.variance;
  }
  return variance > 0 ? (t - mean) / std::sqrt(variance) : 0.0;
}

/// Two-sided p of U from its null distribution's CDF (U is symmetric about nm/2: the smaller
/// tail, doubled).
double p_from_cdf(const std::vector<double>& cdf, double u) {
  const int top = static_cast<int>(cdf.size()) - 1;
  const int k = static_cast<int>(std::floor(std::min(u, top - u) + 1e-9));
  return std::min(1.0, 2 * cdf[std::clamp(k, 0, top)]);
}

}  // namespace

ShiftTest stratified_shift_test(const std::vector<Stratum>& strata, double alpha) {
  if (strata.empty()) throw std::invalid_argument("stratified_shift_test: no strata");
  std::vector<LogStratum> logged;
  std::vector<double> d;
  ShiftTest t;
  for (const Stratum& s : strata) {
    LogStratum l{logs(s.base), logs(s.contender)};
    const double n = static_cast<double>(l.x.size()), m = static_cast<double>(l.y.size());
    std::vector<double> all(l.x);
    all.insert(all.end(), l.y.begin(), l.y.end());
    const double total = n + m;
    l.weight = 1 / (total + 1);
    l.variance =
        n * m / 12 * ((total + 1) - (total > 1 ? tie_sum_of(all) / (total * (total - 1)) : 0.0));
    for (double yj : l.y)
      for (double xi : l.x) d.push_back(yj - xi);
    t.base_count += static_cast<int>(n);
    t.new_count += static_cast<int>(m);
    logged.push_back(std::move(l));
  }
  std::sort(d.begin(), d.end());
  const std::size_t pairs = d.size();
  t.ratio = std::exp(pairs % 2 ? d[pairs / 2] : 0.5 * (d[pairs / 2 - 1] + d[pairs / 2]));
  const double z = stratified_z(logged, 0);
  t.u = z;  // the standardized statistic, in place of a single U
  t.p_value = std::min(1.0, std::erfc(std::abs(z) / std::sqrt(2.0)));
  // The interval: the shifts whose z lies within +-z_crit; z falls as the shift grows.
  const double crit = upper_normal_quantile(alpha / 2);
  const auto shift_where = [&](double target) {
    double lo = d.front() - 1, hi = d.back() + 1;  // z(lo) at its top, z(hi) at its bottom
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (stratified_z(logged, mid) > target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  t.ratio_low = std::exp(shift_where(crit));
  t.ratio_high = std::exp(shift_where(-crit));
  return t;
}

double exact_u_p_value(double u, int n, int m) {
  return p_from_cdf(exact_cdf(n, m), u);
}

ShiftTest shift_test(const std::vector<double>& base, const std::vector<double>& contender,
                     double alpha) {
  const std::vector<double> x = logs(base), y = logs(contender);
  const int n = static_cast<int>(base.size()), m = static_cast<int>(contender.size());
  ShiftTest t;
  t.base_count = n;
  t.new_count = m;
  std::vector<double> d;
  d.reserve(static_cast<std::size_t>(n) * m);
  for (double yj : y)
    for (double xi : x) {
      d.push_back(yj - xi);
      t.u += yj > xi ? 1.0 : yj == xi ? 0.5 : 0.0;
    }
  std::sort(d.begin(), d.end());
  const std::size_t pairs = d.size();
  const double mid = pairs % 2 ? d[pairs / 2] : 0.5 * (d[pairs / 2 - 1] + d[pairs / 2]);
  t.ratio = std::exp(mid);

  // Ties (equal values across both samples) for the variance correction.
  std::vector<double> all(x);
  all.insert(all.end(), y.begin(), y.end());
  const double tie_sum = tie_sum_of(all);
  const double nm = static_cast<double>(n) * m, total = n + m;
  const double variance =
      nm / 12.0 * ((total + 1) - (total > 1 ? tie_sum / (total * (total - 1)) : 0.0));

  // k: the interval's order statistics d_(k) and d_(nm+1-k), 1-based, with P(U < k) <= alpha/2.
  int k = 0;
  if (exact_applies(n, m, tie_sum > 0)) {
    t.exact = true;
    const std::vector<double> cdf = exact_cdf(n, m);  // once: the p and the interval's k
    t.p_value = p_from_cdf(cdf, t.u);
    while (k < static_cast<int>(cdf.size()) && cdf[k] <= alpha / 2) ++k;  // P(U <= k-1) <= a/2
  } else {
    const double sd = std::sqrt(variance);
    const double z = sd > 0 ? (std::abs(t.u - nm / 2) - 0.5) / sd : 0.0;
    t.p_value = sd > 0 ? std::min(1.0, std::erfc(std::max(z, 0.0) / std::sqrt(2.0))) : 1.0;
    k = static_cast<int>(std::floor(nm / 2 - upper_normal_quantile(alpha / 2) * sd));
  }
  // No arrangement is that unlikely (too few samples): the widest interval there is.
  k = std::clamp(k, 1, static_cast<int>((pairs + 1) / 2));
  t.ratio_low = std::exp(d[k - 1]);
  t.ratio_high = std::exp(d[pairs - k]);
  return t;
}

}  // namespace corofem
