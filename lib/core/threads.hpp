#pragma once
// Threads of the step's kernels (OpenMP). One process-wide count, set by --threads before any
// work starts; every parallel kernel splits its work so that its result does not depend on the
// count (each output written by one thread, summed in a fixed order), so runs are bit-identical
// at any count where the algorithm is the same.
#include <functional>
#include <string>
#include <vector>

namespace corofem {

/// Whether the build has OpenMP (without it every kernel runs on one thread).
bool have_openmp();
/// Cores the process may use (the default thread count).
int available_cores();
/// Threads the parallel kernels use.
int thread_count();
/// What a parallel loop runs over, for threads_for: each kind has its own least count of items
/// that makes a second thread pay.
/// - Entries: vector entries, elements and weights.
/// - Blocks: the 3x3 blocks of a matrix (products, smoothing, Galerkin and update passes).
///   Its count is 4x, measured on the 1,536-tet cantilever (4,921 blocks on its fine level) at
///   two threads: at 2,048 blocks a thread the step took 1.17x its one-thread time, with the
///   serial assembly 1.42x (it then reads what the other core's cache holds); at 8,192, 1.005x.
///   Every level of the quadrupeds (18,000 blocks or more) keeps its two threads.
enum class LoopItems { Entries, Blocks };
/// Threads for a loop over `items` units of work: one below a few thousand (forking and joining
/// costs microseconds, and the data a second core touches must come back to the first: more than
/// a small level's whole sweep), else up to thread_count().
/// Results never depend on it: every kernel gives the same bits at any count.
int threads_for(long long items, LoopItems kind = LoopItems::Entries);
/// The least items per thread threads_for() asks for, by kind (the record's context gives both).
long long items_per_thread(LoopItems kind);
/// Sets the entries' count (default 2048; blocks: 4x); the gates set 1 so that small meshes run
/// on every thread they ask for.
void set_items_per_thread(long long items);
/// Sets the count (1..1024); throws InputError naming `what` otherwise. Without OpenMP, only 1.
void set_thread_count(int count, const char* what = "--threads");
/// Parses the value of a --threads option ("all" = available_cores()); throws InputError.
int parse_thread_count(const std::string& value);

/// Runs `a` and `b` at once, one thread each, when thread_count() > 1 (their own parallel loops
/// then run on that one thread), else a then b: for a serial task beside work independent of it.
/// An exception from either is rethrown once both have finished (a's first).
void run_side_by_side(const std::function<void()>& a, const std::function<void()>& b);

/// Sets the count for a scope (a one-thread measurement inside a threaded run) and restores it.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int count) : previous_(thread_count()) { set_thread_count(count); }
  ~ScopedThreadCount() { set_thread_count(previous_); }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_;
};

/// Splits [0, n) into `parts` contiguous ranges of about equal total weight; `weight_prefix` has
/// n + 1 entries (weight_prefix[i] = weight of [0, i)). Returns parts + 1 boundaries.
std::vector<int> balanced_ranges(const std::vector<long long>& weight_prefix, int parts);

}  // namespace corofem
