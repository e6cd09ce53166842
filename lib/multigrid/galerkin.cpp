#include "multigrid/galerkin.hpp"

#include <algorithm>

#include "core/errors.hpp"

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
inline void add_scaled(double* e, double w, const double* a) {
  for (int m = 0; m < 9; ++m) e[m] += w * a[m];
}
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
            add_scaled(sum, r_il * t.r_weight[q], a.values.data() + 9 * p);
            ++p;
            ++q;
          }
        }
      }
      std::copy(sum, sum + 9, e.values.data() + 9 * eb);
    }
  }
}

void GalerkinReuse::apply(const BrcMatrix& a, const Transfer& t, BrcMatrix& e) {
  e.set_zero();
  for (int i = 0; i < e.block_rows; ++i) {
    for (int eb = e.row_start[i]; eb < e.row_start[i + 1]; ++eb) slot_[e.col_index[eb]] = eb;
    for (int m = t.r_start[i]; m < t.r_start[i + 1]; ++m) {
      const int l = t.r_col[m];
      const double r_il = t.r_weight[m];
      for (int b = a.row_start[l]; b < a.row_start[l + 1]; ++b) {
        const int k = a.col_index[b];
        const double* ab = a.values.data() + 9 * b;
        for (int n = t.p_start[k]; n < t.p_start[k + 1]; ++n)
          add_scaled(e.values.data() + 9 * slot_[t.p_col[n]], r_il * t.p_weight[n], ab);
      }
    }
  }
}

GalerkinStream::GalerkinStream(const BrcMatrix& a, const Transfer& t, const BrcMatrix& e,
                               Symmetry symmetry) {
  const bool upper_only = symmetry == Symmetry::Symmetric;
  control_.reserve(a.num_blocks());
  for (int l = 0; l < a.block_rows; ++l) {
    for (int b = a.row_start[l]; b < a.row_start[l + 1]; ++b) {
      const int k = a.col_index[b];
      std::size_t count = 0;
      for (int m = t.p_start[l]; m < t.p_start[l + 1]; ++m) {
        const int i = t.p_col[m];
        for (int n = t.p_start[k]; n < t.p_start[k + 1]; ++n) {
          const int j = t.p_col[n];
          if (upper_only && j < i) continue;
          data_.push_back({t.p_weight[m] * t.p_weight[n], static_cast<std::uint32_t>(e.find(i, j))});
          ++count;
        }
      }
      // setNext(): one byte with the top bit set, then continuation bytes of at most 127 pairs.
      const std::size_t first = std::min<std::size_t>(count, 127);
      control_.push_back(static_cast<std::uint8_t>(0x80 | first));
      for (std::size_t left = count - first; left > 0;) {
        const std::size_t chunk = std::min<std::size_t>(left, 127);
        control_.push_back(static_cast<std::uint8_t>(chunk));
        left -= chunk;
      }
    }
  }
  if (upper_only)
    for (int i = 0; i < e.block_rows; ++i)
      for (int b = e.row_start[i]; b < e.row_start[i + 1]; ++b)
        if (e.col_index[b] > i)
          mirror_.emplace_back(static_cast<std::uint32_t>(b),
                               static_cast<std::uint32_t>(e.find(e.col_index[b], i)));
}

void GalerkinStream::apply(const BrcMatrix& a, BrcMatrix& e) const {
  e.set_zero();
  const double* block = a.values.data() - 9;
  const Pair* pair = data_.data();
  double* ev = e.values.data();
  for (const std::uint8_t c : control_) {
    if (c & 0x80) block += 9;  // step 1: advance to the next block of A
    for (int p = c & 0x7f; p > 0; --p, ++pair)  // step 2: p weighted scatters
      add_scaled(ev + 9 * static_cast<std::size_t>(pair->destination), pair->weight, block);
  }
  for (const auto& [upper, lower] : mirror_) {  // E_ji = E_ij^T
    const double* u = ev + 9 * static_cast<std::size_t>(upper);
    double* l = ev + 9 * static_cast<std::size_t>(lower);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) l[3 * r + c] = u[3 * c + r];
  }
}

GalerkinMethod galerkin_method(const std::string& name) {
  if (name == "naive") return GalerkinMethod::Naive;
  if (name == "stream") return GalerkinMethod::Stream;
  if (name == "stream-full") return GalerkinMethod::StreamFull;
  if (name == "reuse") return GalerkinMethod::Reuse;
  throw InputError("analysis.galerkin: unknown method '" + name + "' (known: naive, stream, stream-full, reuse)");
}

}  // namespace corofem
