#pragma once
// Order statistics for records: medians of phase times, iterations and convergence factors.
#include <vector>

namespace corofem {

/// Median of the values (NaN for none).
double median(std::vector<double> values);

}  // namespace corofem
