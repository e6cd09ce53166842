#include "core/machine_roofs.hpp"

#include <Eigen/Core>
#include <chrono>
#include <vector>

#include "core/statistics.hpp"
#include "core/threads.hpp"

namespace corofem {

void stream_triad(double* a, const double* b, const double* c, double s, std::size_t n) {
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) num_threads(thread_count())
  for (std::ptrdiff_t i = 0; i < count; ++i) a[i] = b[i] + s * c[i];
}

double measure_stream_triad_gbps(int repetitions, std::size_t elements) {
  std::vector<double> a(elements), b(elements), c(elements);
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(elements);
#pragma omp parallel for schedule(static) num_threads(thread_count())
  for (std::ptrdiff_t i = 0; i < count; ++i) {  // first touch by the thread that will stream it
    a[i] = 0.0;
    b[i] = 1.0;
    c[i] = 2.0;
  }
  stream_triad(a.data(), b.data(), c.data(), 3.0, elements);  // pages touched before timing
  std::vector<double> rates;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    stream_triad(a.data(), b.data(), c.data(), 3.0 + r, elements);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(24.0 * static_cast<double>(elements) / seconds / 1e9);
  }
  volatile double sink = a[elements / 2];  // the passes have an observable result
  (void)sink;
  return median(rates);
}

double measure_dense_gflops(int repetitions, int n) {
  const int threads = thread_count();
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
  std::vector<Eigen::MatrixXd> c(threads, Eigen::MatrixXd(n, n));
  const auto products = [&] {  // one product per thread, all at once
#pragma omp parallel for schedule(static, 1) num_threads(threads)
    for (int t = 0; t < threads; ++t) c[t].noalias() = a * b;
  };
  products();  // warm: caches, page faults
  std::vector<double> rates;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    products();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(2.0 * threads * n * n * static_cast<double>(n) / seconds / 1e9);
  }
  volatile double sink = c[0](n / 2, n / 2);
  (void)sink;
  return median(rates);
}

}  // namespace corofem
