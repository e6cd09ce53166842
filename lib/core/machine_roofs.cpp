#include "core/machine_roofs.hpp"

#include <Eigen/Core>
#include <chrono>
#include <vector>

#include "core/statistics.hpp"

namespace corofem {

void stream_triad(double* a, const double* b, const double* c, double s, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
}

double measure_stream_triad_gbps(int repetitions, std::size_t elements) {
  std::vector<double> a(elements, 0.0), b(elements, 1.0), c(elements, 2.0);
  stream_triad(a.data(), b.data(), c.data(), 3.0, elements);  // pages touched before timing
  std::vector<double> rates;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    stream_triad(a.data(), b.data(), c.data(), 3.0 + r, elements);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(24.0 * static_cast<double>(elements) / seconds / 1e9);
  }
  volatile double sink = a[elements / 2];  // the passes have an observable result
  (void)sink;
  return median(rates);
}

double measure_dense_gflops(int repetitions, int n) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd c(n, n);
  c.noalias() = a * b;  // warm: caches, page faults
  std::vector<double> rates;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    c.noalias() = a * b;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(2.0 * n * n * static_cast<double>(n) / seconds / 1e9);
  }
  volatile double sink = c(n / 2, n / 2);
  (void)sink;
  return median(rates);
}

}  // namespace corofem
