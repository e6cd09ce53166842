#pragma once
// Order statistics for records: medians of phase times, iterations and convergence factors, and
// the Pareto front of points of cost and error.
#include <vector>

namespace corofem {

/// Median of the values (NaN for none).
double median(std::vector<double> values);

/// A time sample as records keep it: to 0.1 microseconds (finer is below the clock's own noise,
/// and it keeps a record of a few thousand samples small).
double rounded_sample_ms(double ms);

struct CostAndError {
  double cost, error;
};

/// Per point: whether no other point is at least as good in both and better in one (the Pareto
/// front of cost against error).
std::vector<bool> pareto_front(const std::vector<CostAndError>& points);

}  // namespace corofem
