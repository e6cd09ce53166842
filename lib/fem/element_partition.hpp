#pragma once
// Owner-computes partition for threaded assembly: the vertices (block rows) split into contiguous
// ranges, one per thread, and for each range the elements touching it. A thread writes only the
// rows it owns, visiting its elements in ascending order, so every block receives its element
// contributions in the same order at any thread count: the sums are bit-identical to one thread.
// Elements on a range boundary are visited by each thread that owns one of their vertices.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct RowPartition {
  std::vector<int> row_begin;              ///< parts + 1 vertex boundaries
  std::vector<std::vector<int>> elements;  ///< per part, ascending element indices

  int parts() const { return static_cast<int>(elements.size()); }
  /// Fraction of element visits beyond one per element (the boundary's duplicated work).
  double duplication() const;
};

/// Balanced by incident elements per vertex (the work of a row).
RowPartition partition_rows(const std::vector<Tet>& tets, int num_vertices, int parts);

/// Runs f(part) for every part on up to thread_count() threads (one for a small mesh).
template <class F>
void for_each_part(const RowPartition& partition, const F& f);

}  // namespace corofem

#include "core/threads.hpp"

namespace corofem {

template <class F>
void for_each_part(const RowPartition& partition, const F& f) {
  const int parts = partition.parts();
  long long visits = 0;  // element visits: the work
  for (const auto& list : partition.elements) visits += static_cast<long long>(list.size());
  const int threads = threads_for(visits);
#pragma omp parallel for schedule(static, 1) num_threads(threads < parts ? threads : parts)
  for (int p = 0; p < parts; ++p) f(p);
}

}  // namespace corofem
