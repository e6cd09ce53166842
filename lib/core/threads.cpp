#include "core/threads.hpp"

#include <algorithm>
#include <exception>
#include <string>
#include <thread>

#include "core/errors.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace corofem {

namespace {
int g_threads = 0;  // 0: not set: the process's default
long long g_items_per_thread = 2048;
#ifdef _OPENMP
// Read before main: libraries (gmsh) change OpenMP's own count when they run, so every parallel
// region of ours names its count (num_threads(thread_count())) rather than inheriting it.
const int g_default_threads = std::max(1, omp_get_max_threads());  // honours OMP_NUM_THREADS
#endif
}  // namespace

bool have_openmp() {
#ifdef _OPENMP
  return true;
#else
  return false;
#endif
}

int available_cores() {
#ifdef _OPENMP
  return std::max(1, omp_get_num_procs());
#else
  return 1;
#endif
}

int thread_count() {
#ifdef _OPENMP
  return g_threads > 0 ? g_threads : g_default_threads;
#else
  return 1;
#endif
}

long long items_per_thread(LoopItems kind) {
  return kind == LoopItems::Blocks ? 4 * g_items_per_thread : g_items_per_thread;
}

int threads_for(long long items, LoopItems kind) {
  const long long useful = items / items_per_thread(kind);
  return static_cast<int>(std::max(1LL, std::min<long long>(thread_count(), useful)));
}

void set_items_per_thread(long long items) {
  g_items_per_thread = std::max(1LL, items);
}

void set_thread_count(int count, const char* what) {
  if (count < 1 || count > 1024)
    throw InputError(std::string(what) + ": " + std::to_string(count) +
                     " threads (give 1..1024 or all)");
  if (count > 1 && !have_openmp())
    throw InputError(std::string(what) + ": " + std::to_string(count) +
                     " threads, but this build has no OpenMP (only 1)");
  g_threads = count;
#ifdef _OPENMP
  omp_set_num_threads(count);
#endif
}

int parse_thread_count(const std::string& value) {
  if (value == "all") return available_cores();
  std::size_t used = 0;
  int count = 0;
  try {
    count = std::stoi(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size())
    throw InputError("--threads: '" + value + "' is not a thread count (give 1..1024 or all)");
  return count;
}

std::vector<int> balanced_ranges(const std::vector<long long>& weight_prefix, int parts) {
  const int n = static_cast<int>(weight_prefix.size()) - 1;
  std::vector<int> bounds(parts + 1, n);
  bounds[0] = 0;
  const long long total = weight_prefix.back();
  for (int p = 1; p < parts; ++p) {
    const long long target = total * p / parts;
    // The boundary whose prefix is nearest the target; never before the previous boundary.
    const auto it =
        std::lower_bound(weight_prefix.begin() + bounds[p - 1], weight_prefix.end() - 1, target);
    int b = static_cast<int>(it - weight_prefix.begin());
    if (b > bounds[p - 1] && target - weight_prefix[b - 1] < weight_prefix[b] - target) --b;
    bounds[p] = b;
  }
  return bounds;
}

void run_side_by_side(const std::function<void()>& a, const std::function<void()>& b) {
  std::exception_ptr failed[2];
  const auto run = [&](int which) {
    try {
      (which == 0 ? a : b)();
    } catch (...) {
      failed[which] = std::current_exception();  // no exception may leave a parallel region
    }
  };
#ifdef _OPENMP
  if (thread_count() > 1) {
#pragma omp parallel num_threads(2)
    run(omp_get_thread_num());
  } else {
    run(0);
    run(1);
  }
#else
  run(0);
  run(1);
#endif
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace corofem
