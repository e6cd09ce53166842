#include "core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace corofem {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double rounded_sample_ms(double ms) {
  return std::round(ms * 1e4) / 1e4;
}

std::vector<bool> pareto_front(const std::vector<CostAndError>& points) {
  std::vector<bool> front(points.size(), true);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const CostAndError& q : points) {
      const CostAndError& p = points[i];
      if (q.cost <= p.cost && q.error <= p.error && (q.cost < p.cost || q.error < p.error))
        front[i] = false;
    }
  return front;
}

}  // namespace corofem
