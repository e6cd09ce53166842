#include "multigrid/galerkin_gather.hpp"

#include "core/threads.hpp"
#include "multigrid/galerkin.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {
namespace {

/// Blocks [first, last) of blocks_: each the sum of its pairs' w A_k, from zero, in the pairs'
/// order, each entry e += w a as add_scaled_block_scalar (the stream's scalar form).
void gather_scalar(const std::uint32_t* blocks, const std::uint32_t* start, std::size_t first,
                   std::size_t last, const GalerkinGather::Pair* pairs, const double* av,
                   double* ev) {
  for (std::size_t u = first; u < last; ++u) {
    double s[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    for (std::uint32_t c = start[u]; c < start[u + 1]; ++c) {
      const double w = pairs[c].weight;
      const double* a = av + 9 * static_cast<std::size_t>(pairs[c].source);
      for (int m = 0; m < 9; ++m) s[m] += w * a[m];
    }
    double* e = ev + 9 * static_cast<std::size_t>(blocks[u]);
    for (int m = 0; m < 9; ++m) e[m] = s[m];
  }
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// The same with add_scaled_block_avx2's operations (two 4-wide FMAs and one scalar FMA), the
/// sums held in registers.
__attribute__((target("avx2,fma"))) void gather_avx2(const std::uint32_t* blocks,
                                                     const std::uint32_t* start, std::size_t first,
                                                     std::size_t last,
                                                     const GalerkinGather::Pair* pairs,
                                                     const double* av, double* ev) {
  for (std::size_t u = first; u < last; ++u) {
    __m256d s0 = _mm256_setzero_pd(), s1 = _mm256_setzero_pd();
    double s2 = 0;
    for (std::uint32_t c = start[u]; c < start[u + 1]; ++c) {
      const double w = pairs[c].weight;
      const double* a = av + 9 * static_cast<std::size_t>(pairs[c].source);
      const __m256d weight = _mm256_set1_pd(w);
      s0 = _mm256_fmadd_pd(weight, _mm256_loadu_pd(a), s0);
      s1 = _mm256_fmadd_pd(weight, _mm256_loadu_pd(a + 4), s1);
      s2 = __builtin_fma(w, a[8], s2);
    }
    double* e = ev + 9 * static_cast<std::size_t>(blocks[u]);
    _mm256_storeu_pd(e, s0);
    _mm256_storeu_pd(e + 4, s1);
    e[8] = s2;
  }
}
#endif

}  // namespace

GalerkinGather::GalerkinGather(const BrcMatrix& a, const Transfer& t, const BrcMatrix& e,
                               int parts) {
  // Pair counts per block of E, then the pairs in A's storage order into their blocks' ranges.
  std::vector<std::uint32_t> count(e.num_blocks(), 0);
  for_each_galerkin_pair(a, t, true, [&](int, int i, int j, double) { ++count[e.find(i, j)]; });
  std::vector<long long> prefix(e.block_rows + 1, 0);  // pairs per row of E: the threads' work
  std::vector<std::uint32_t> slot(e.num_blocks(), 0);  // block of E -> its position in blocks_
  start_.push_back(0);
  for (int i = 0; i < e.block_rows; ++i) {
    for (int b = e.row_start[i]; b < e.row_start[i + 1]; ++b) {
      if (e.col_index[b] < i) continue;  // mirrored
      slot[b] = static_cast<std::uint32_t>(blocks_.size());
      blocks_.push_back(static_cast<std::uint32_t>(b));
      start_.push_back(start_.back() + count[b]);
      prefix[i + 1] += count[b];
    }
    prefix[i + 1] += prefix[i];
  }
  pairs_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for_each_galerkin_pair(a, t, true, [&](int b, int i, int j, double weight) {
    pairs_[next[slot[e.find(i, j)]]++] = {weight, static_cast<std::uint32_t>(b)};
  });
  // Parts: ranges of E's rows of about equal pair counts, as positions in blocks_.
  const std::vector<int> rows = balanced_ranges(prefix, parts > 0 ? parts : thread_count());
  std::size_t u = 0;
  part_start_.push_back(0);
  for (std::size_t p = 1; p < rows.size(); ++p) {
    const std::uint32_t end = static_cast<std::uint32_t>(e.row_start[rows[p]]);
    while (u < blocks_.size() && blocks_[u] < end) ++u;
    part_start_.push_back(u);
  }
  mirror_ = galerkin_mirror_pairs(e);
}

std::size_t GalerkinGather::bytes() const {
  return pairs_.size() * sizeof(Pair) + (blocks_.size() + start_.size()) * sizeof(std::uint32_t);
}

void GalerkinGather::apply(const BrcMatrix& a, BrcMatrix& e) const {
  double* ev = e.values.data();
  const double* av = a.values.data();
  const int parts = static_cast<int>(part_start_.size()) - 1;
  const int threads = threads_for(a.num_blocks(), LoopItems::Blocks);
#pragma omp parallel num_threads(threads < parts ? threads : parts)
  {
#pragma omp for schedule(static, 1)
    for (int p = 0; p < parts; ++p) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
      if (vector_block_kernels()) {
        gather_avx2(blocks_.data(), start_.data(), part_start_[p], part_start_[p + 1],
                    pairs_.data(), av, ev);
        continue;
      }
#endif
      gather_scalar(blocks_.data(), start_.data(), part_start_[p], part_start_[p + 1],
                    pairs_.data(), av, ev);
    }
    mirror_blocks(mirror_, ev);
  }
}

}  // namespace corofem
