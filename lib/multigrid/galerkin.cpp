#include "multigrid/galerkin.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {

BrcMatrix galerkin_pattern(const BrcMatrix& a, const Transfer& t) {
  std::vector<std::vector<int>> columns(t.coarse);
  std::vector<int> mark(t.coarse, -1);
  for (int i = 0; i < t.coarse; ++i) {
    for (int m = t.r_start[i]; m < t.r_start[i + 1]; ++m) {
      const int l = t.r_col[m];
      for (int b = a.row_start[l]; b < a.row_start[l + 1]; ++b) {
        const int k = a.col_index[b];
        for (int n = t.p_start[k]; n < t.p_start[k + 1]; ++n) {
          const int j = t.p_col[n];
          if (mark[j] != i) {
            mark[j] = i;
            columns[i].push_back(j);
          }
        }
      }
    }
    std::sort(columns[i].begin(), columns[i].end());
  }
  return make_brc_pattern(t.coarse, columns);
}

namespace {

/// One part's numeric phase (paper 4.2): per control byte, step 1 advances to A's next block,
/// step 2 adds its n weighted copies into their blocks of E.
template <class AddScaled>
inline void run_stream(const std::vector<std::uint8_t>& control, const GalerkinStream::Pair* pair,
                       const double* av, double* ev, const AddScaled& add_scaled) {
  const double* block = av - 9;
  for (const std::uint8_t c : control) {
    if (c & 0x80) block += 9;
    for (int n = c & 0x7f; n > 0; --n, ++pair)
      add_scaled(ev + 9 * static_cast<std::size_t>(pair->destination), pair->weight, block);
  }
}

void run_stream_scalar(const std::vector<std::uint8_t>& control, const GalerkinStream::Pair* pair,
                       const double* av, double* ev) {
  run_stream(control, pair, av, ev, add_scaled_block_scalar);
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void run_stream_avx2(const std::vector<std::uint8_t>& control,
                                                         const GalerkinStream::Pair* pair,
                                                         const double* av, double* ev) {
  // The function itself, not a lambda around it: a lambda is compiled without AVX2, and could
  // only call the AVX2 add, pair by pair, instead of inlining it.
  run_stream(control, pair, av, ev, add_scaled_block_avx2);
}
#endif

}  // namespace

void galerkin_naive(const BrcMatrix& a, const Transfer& t, BrcMatrix& e) {
  for (int i = 0; i < e.block_rows; ++i) {
    for (int eb = e.row_start[i]; eb < e.row_start[i + 1]; ++eb) {
      const int j = e.col_index[eb];
      double sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (int m = t.r_start[i]; m < t.r_start[i + 1]; ++m) {
        const int l = t.r_col[m];
        const double r_il = t.r_weight[m];
        // Merge the sorted sets S_l^A (columns of A's row l) and S_j^R (fine columns of R's row j).
        int p = a.row_start[l], p_end = a.row_start[l + 1];
        int q = t.r_start[j], q_end = t.r_start[j + 1];
        while (p < p_end && q < q_end) {
          const int ka = a.col_index[p], kr = t.r_col[q];
          if (ka < kr) {
            ++p;
          } else if (kr < ka) {
            ++q;
          } else {
            add_scaled_block_scalar(sum, r_il * t.r_weight[q], a.values.data() + 9 * p);
            ++p;
            ++q;
          }
        }
      }
      std::copy(sum, sum + 9, e.values.data() + 9 * eb);
    }
  }
}

namespace {

/// Pattern reuse's numeric phase: per row i of E, its blocks' slots, then every R_il A_lk R_jk
/// added into E_ij. The scatter in either form (the stream's kernel, so that their ratio is the
/// algorithms').
template <class AddScaled>
inline void reuse_rows(const BrcMatrix& a, const Transfer& t, BrcMatrix& e, int* slot,
                       const AddScaled& add_scaled) {
  for (int i = 0; i < e.block_rows; ++i) {
    for (int eb = e.row_start[i]; eb < e.row_start[i + 1]; ++eb) slot[e.col_index[eb]] = eb;
    for (int m = t.r_start[i]; m < t.r_start[i + 1]; ++m) {
      const int l = t.r_col[m];
      const double r_il = t.r_weight[m];
      for (int b = a.row_start[l]; b < a.row_start[l + 1]; ++b) {
        const int k = a.col_index[b];
        const double* ab = a.values.data() + 9 * b;
        for (int n = t.p_start[k]; n < t.p_start[k + 1]; ++n)
          add_scaled(e.values.data() + 9 * slot[t.p_col[n]], r_il * t.p_weight[n], ab);
      }
    }
  }
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void reuse_rows_avx2(const BrcMatrix& a, const Transfer& t,
                                                         BrcMatrix& e, int* slot) {
  reuse_rows(a, t, e, slot, add_scaled_block_avx2);
}
#endif

}  // namespace

void GalerkinReuse::apply(const BrcMatrix& a, const Transfer& t, BrcMatrix& e) {
  e.set_zero();
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels()) return reuse_rows_avx2(a, t, e, slot_.data());
#endif
  reuse_rows(a, t, e, slot_.data(), add_scaled_block_scalar);
}

namespace {

/// setNext(): one byte with the top bit set, then continuation bytes of at most 127 pairs.
void append_control(std::vector<std::uint8_t>& control, std::size_t count) {
  const std::size_t first = std::min<std::size_t>(count, 127);
  control.push_back(static_cast<std::uint8_t>(0x80 | first));
  for (std::size_t left = count - first; left > 0;) {
    const std::size_t chunk = std::min<std::size_t>(left, 127);
    control.push_back(static_cast<std::uint8_t>(chunk));
    left -= chunk;
  }
}

}  // namespace

GalerkinStream::GalerkinStream(const BrcMatrix& a, const Transfer& t, const BrcMatrix& e,
                               Symmetry symmetry, int parts) {
  const bool upper_only = symmetry == Symmetry::Symmetric;
  const auto for_each_pair = [&](const auto& f) { for_each_galerkin_pair(a, t, upper_only, f); };
  // Rows of E split by their pair counts (the numeric phase's work).
  std::vector<long long> prefix(e.block_rows + 1, 0);
  for_each_pair([&](int, int i, int, double) { ++prefix[i + 1]; });
  for (int i = 0; i < e.block_rows; ++i) prefix[i + 1] += prefix[i];
  const std::vector<int> rows = balanced_ranges(prefix, parts > 0 ? parts : thread_count());
  parts_.resize(rows.size() - 1);
  std::vector<int> part_of(e.block_rows);
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    parts_[p].row_lo = rows[p];
    parts_[p].row_hi = rows[p + 1];
    parts_[p].control.reserve(a.num_blocks());
    for (int i = rows[p]; i < rows[p + 1]; ++i) part_of[i] = static_cast<int>(p);
  }
  std::vector<std::size_t> count(parts_.size(), 0);
  int closed = 0;  // blocks of A whose control bytes are written
  const auto close_block = [&] {
    for (std::size_t p = 0; p < parts_.size(); ++p) append_control(parts_[p].control, count[p]);
    std::fill(count.begin(), count.end(), 0);
    ++closed;
  };
  for_each_pair([&](int b, int i, int j, double weight) {
    while (closed < b) close_block();
    const int p = part_of[i];
    parts_[p].data.push_back({weight, static_cast<std::uint32_t>(e.find(i, j))});
    ++count[p];
  });
  while (closed < a.num_blocks()) close_block();
  if (upper_only) mirror_ = galerkin_mirror_pairs(e);
}

MirrorPairs galerkin_mirror_pairs(const BrcMatrix& e) {
  MirrorPairs mirror;
  for (int i = 0; i < e.block_rows; ++i)
    for (int b = e.row_start[i]; b < e.row_start[i + 1]; ++b)
      if (e.col_index[b] > i)
        mirror.emplace_back(static_cast<std::uint32_t>(b),
                            static_cast<std::uint32_t>(e.find(e.col_index[b], i)));
  return mirror;
}

void mirror_blocks(const MirrorPairs& mirror, double* ev) {
  const std::ptrdiff_t pairs = static_cast<std::ptrdiff_t>(mirror.size());
#pragma omp for schedule(static)
  for (std::ptrdiff_t m = 0; m < pairs; ++m) {  // E_ji = E_ij^T
    const double* u = ev + 9 * static_cast<std::size_t>(mirror[m].first);
    double* l = ev + 9 * static_cast<std::size_t>(mirror[m].second);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) l[3 * r + c] = u[3 * c + r];
  }
}

std::size_t GalerkinStream::num_pairs() const {
  std::size_t pairs = 0;
  for (const Part& part : parts_) pairs += part.data.size();
  return pairs;
}

std::size_t GalerkinStream::bytes() const {
  std::size_t bytes = 0;
  for (const Part& part : parts_) bytes += part.control.size() + part.data.size() * sizeof(Pair);
  return bytes;
}

void GalerkinStream::apply(const BrcMatrix& a, BrcMatrix& e) const {
  double* ev = e.values.data();
  const int parts = static_cast<int>(parts_.size());
  const int threads = threads_for(a.num_blocks(), LoopItems::Blocks);
#pragma omp parallel num_threads(threads < parts ? threads : parts)
  {
#pragma omp for schedule(static, 1)
    for (int p = 0; p < parts; ++p) {
      const Part& part = parts_[p];
      std::fill(ev + 9 * static_cast<std::size_t>(e.row_start[part.row_lo]),
                ev + 9 * static_cast<std::size_t>(e.row_start[part.row_hi]), 0.0);
#ifdef COROFEM_HAVE_AVX2_KERNELS
      if (vector_block_kernels()) {
        run_stream_avx2(part.control, part.data.data(), a.values.data(), ev);
        continue;
      }
#endif
      run_stream_scalar(part.control, part.data.data(), a.values.data(), ev);
    }
    mirror_blocks(mirror_, ev);
  }
}

}  // namespace corofem
