#include "linalg/gauss_seidel.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {

namespace {

/// out = (m + diag(l1))^-1 by the cofactors; m and out row-major 3x3.
inline void invert_block(const double* m, const double l1[3], double* out) {
  const double a = m[0] + l1[0], b = m[1], c = m[2];
  const double d = m[3], e = m[4] + l1[1], f = m[5];
  const double g = m[6], h = m[7], k = m[8] + l1[2];
  const double c00 = e * k - f * h, c10 = f * g - d * k, c20 = d * h - e * g;
  const double s = 1.0 / (a * c00 + b * c10 + c * c20);
  out[0] = c00 * s;
  out[1] = (c * h - b * k) * s;
  out[2] = (b * f - c * e) * s;
  out[3] = c10 * s;
  out[4] = (a * k - c * g) * s;
  out[5] = (c * d - a * f) * s;
  out[6] = c20 * s;
  out[7] = (b * g - a * h) * s;
  out[8] = (a * e - b * d) * s;
}

/// Greedy colouring of the rows `which` (ascending) in the block graph: each takes the smallest
/// colour none of its neighbours among them has. Returns them grouped by colour (ascending within).
void colour_rows(const BrcMatrix& a, const std::vector<int>& which, std::vector<int>& start,
                 std::vector<int>& rows) {
  std::vector<int> colour(a.block_rows, -1), used;  // used[c] == i: colour c taken around row i
  int colours = 0;
  for (const int i : which) {
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      const int c = colour[a.col_index[k]];
      if (c >= 0) used[c] = i;
    }
    int c = 0;
    while (c < colours && used[c] == i) ++c;
    if (c == colours) {
      ++colours;
      used.push_back(-1);
    }
    colour[i] = c;
  }
  start.assign(colours + 1, 0);
  for (const int i : which) ++start[colour[i] + 1];
  for (int c = 0; c < colours; ++c) start[c + 1] += start[c];
  rows.resize(which.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (const int i : which) rows[next[colour[i]]++] = i;
}

}  // namespace

void BlockGaussSeidel::set_matrix(const BrcMatrix& a) {
  if (!ordered_) order_rows(a);  // the pattern never changes: ordered once
  const bool hybrid = ordering_ == SmootherOrdering::Hybrid;
  inverse_diagonal_.resize(a.block_rows);
  if (hybrid) l1_.resize(3 * a.block_rows);
  // One pass down the rows: each row's diagonal block, plus for the hybrid smoother the l1 norms
  // of the row's entries outside its domain (at its start and end: the columns are sorted),
  // inverted by its cofactors. The rows' blocks lie a row apart: the diagonal block and the
  // row's off-domain blocks, every line of them, are fetched kAhead rows ahead, or each read
  // waits on memory (lib/docs/multigrid-update-notes.md, "The smoothers' set-up against its
  // floor").
  constexpr int kAhead = 16;
  const double* values = a.values.data();
  const auto fetch_blocks = [&](int from, int to) {  // blocks [from, to): every line
    const char* begin = reinterpret_cast<const char*>(values + 9 * static_cast<std::size_t>(from));
    const char* end = reinterpret_cast<const char*>(values + 9 * static_cast<std::size_t>(to));
    for (const char* line = begin; line < end; line += 64) __builtin_prefetch(line);
    __builtin_prefetch(end - 1);
  };
#pragma omp parallel for schedule(static) num_threads(threads_for(a.block_rows))
  for (int i = 0; i < a.block_rows; ++i) {
    if (i + kAhead < a.block_rows) {
      const int ahead = i + kAhead;
      fetch_blocks(diagonal_block_[ahead], diagonal_block_[ahead] + 1);
      if (hybrid && own_begin_[ahead] != a.row_start[ahead])
        fetch_blocks(a.row_start[ahead], own_begin_[ahead]);
      if (hybrid && own_end_[ahead] != a.row_start[ahead + 1])
        fetch_blocks(own_end_[ahead], a.row_start[ahead + 1]);
    }
    double l1[3] = {0, 0, 0};
    if (hybrid) {
      const auto add = [&](int from, int to) {
        for (int k = from; k < to; ++k) {
          const double* m = values + 9 * static_cast<std::size_t>(k);
          for (int r = 0; r < 3; ++r)
            l1[r] += std::abs(m[3 * r]) + std::abs(m[3 * r + 1]) + std::abs(m[3 * r + 2]);
        }
      };
      add(a.row_start[i], own_begin_[i]);
      add(own_end_[i], a.row_start[i + 1]);
      for (int r = 0; r < 3; ++r) l1_[3 * i + r] = l1[r];
    }
    invert_block(values + 9 * static_cast<std::size_t>(diagonal_block_[i]), l1,
                 inverse_diagonal_[i].data());
  }
}

void BlockGaussSeidel::order_rows(const BrcMatrix& a) {
  diagonal_block_.resize(a.block_rows);
  for (int i = 0; i < a.block_rows; ++i) {
    diagonal_block_[i] = a.find(i, i);
    if (diagonal_block_[i] < 0) throw NumericalFault("multigrid: a level has no diagonal block");
  }
  ordered_ = true;
  std::vector<int> all(a.block_rows);
  for (int i = 0; i < a.block_rows; ++i) all[i] = i;
  if (ordering_ == SmootherOrdering::Multicolour) colour_rows(a, all, colour_start_, colour_rows_);
  if (ordering_ == SmootherOrdering::Hybrid) order_hybrid(a);
  if (ordering_ != SmootherOrdering::Domains) return;
  // Contiguous domains of equal block counts; a row is interior when all its columns are in it.
  const int domains = std::max(1, a.block_rows / domain_size_);  // never the thread count
  std::vector<long long> prefix(a.row_start.begin(), a.row_start.end());
  const std::vector<int> bounds = balanced_ranges(prefix, domains);
  std::vector<int> boundary;
  domain_start_.assign(1, 0);
  domain_rows_.clear();
  for (int d = 0; d < domains; ++d) {
    for (int i = bounds[d]; i < bounds[d + 1]; ++i) {
      bool interior = true;
      for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
        interior &= a.col_index[k] >= bounds[d] && a.col_index[k] < bounds[d + 1];
      (interior ? domain_rows_ : boundary).push_back(i);
    }
    domain_start_.push_back(static_cast<int>(domain_rows_.size()));
  }
  colour_rows(a, boundary, colour_start_, colour_rows_);
}

void BlockGaussSeidel::order_hybrid(const BrcMatrix& a) {
  // Domains of at most domain_size_ blocks, as few as that allows (rounding the count down left
  // the bunny's fine level and the horse's first coarse one, 33501 and 43744 blocks, one domain,
  // so one thread); an even count (when more than one) balances two threads; never the thread
  // count itself.
  const long long blocks = static_cast<long long>(a.col_index.size());
  int domains = std::max(1, static_cast<int>((blocks + domain_size_ - 1) / domain_size_));
  if (domains > 1 && domains % 2 == 1) ++domains;
  std::vector<long long> prefix(a.row_start.begin(), a.row_start.end());
  domain_start_ = balanced_ranges(prefix, domains);
  own_begin_.resize(a.block_rows);
  own_end_.resize(a.block_rows);
  halo_rows_.clear();
  off_domain_blocks_ = 0;
  for (int d = 0; d < domains; ++d) {
    const int lo = domain_start_[d], hi = domain_start_[d + 1];
    for (int i = lo; i < hi; ++i) {
      const auto first = a.col_index.begin() + a.row_start[i],
                 last = a.col_index.begin() + a.row_start[i + 1];
      own_begin_[i] = static_cast<int>(std::lower_bound(first, last, lo) - a.col_index.begin());
      own_end_[i] = static_cast<int>(std::lower_bound(first, last, hi) - a.col_index.begin());
      if (own_begin_[i] != a.row_start[i] || own_end_[i] != a.row_start[i + 1])
        halo_rows_.push_back(i);
      off_domain_blocks_ += (own_begin_[i] - a.row_start[i]) + (a.row_start[i + 1] - own_end_[i]);
    }
  }
}

namespace {

/// x_i = D^{-1} r with D^{-1} row-major.
inline void solve_diagonal(const double* inverse, const double r[3], double* xi) {
  xi[0] = inverse[0] * r[0] + inverse[1] * r[1] + inverse[2] * r[2];
  xi[1] = inverse[3] * r[0] + inverse[4] * r[1] + inverse[5] * r[2];
  xi[2] = inverse[6] * r[0] + inverse[7] * r[1] + inverse[8] * r[2];
}

}  // namespace

template <bool Hybrid, bool Backward>
void BlockGaussSeidel::relax_row(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                 int i, int lo, int hi) const {
  // x_i += M_ii^{-1} (b_i - sum_j A_ij y_j), y_j = x_j in the own domain [lo, hi) (x_i itself
  // included), frozen_j outside it: for the hybrid smoother M_ii = D + D_l1, and this is
  // (D + D_l1) x_i' = b_i + D_l1 x_i - sum_{j != i} A_ij y_j: one loop over the row, x or the
  // frozen copy chosen per block, and no l1 vector to read. A backward sweep reads the row's
  // blocks backwards too: the whole sweep then streams the matrix downwards, which the hardware
  // prefetchers follow; ascending blocks in descending rows made the backward sweep 2.8x a
  // product against the forward one's 1.3x (BM_SmootherSweep).
  double* xs = x.data();
  const double* frozen = Hybrid ? frozen_.data() : xs;
  const unsigned width = static_cast<unsigned>(hi - lo);
  auto source = [=](int j) {
    return (Hybrid && static_cast<unsigned>(j - lo) >= width ? frozen : xs) + 3 * j;
  };
  double s[3];
  block_row_sum<Backward, true>(a.col_index.data(), a.values.data(), a.row_start[i],
                                a.row_start[i + 1], source, s);
  const double r[3] = {b[3 * i] - s[0], b[3 * i + 1] - s[1], b[3 * i + 2] - s[2]};
  double dx[3];
  solve_diagonal(inverse_diagonal_[i].data(), r, dx);
  for (int c = 0; c < 3; ++c) xs[3 * i + c] += dx[c];
}

void BlockGaussSeidel::forward_from_zero(const BrcMatrix& a, const Eigen::VectorXd& b,
                                         Eigen::VectorXd& x) const {
  sweep_from_zero(a, b, x, nullptr);
}

void BlockGaussSeidel::forward_from_zero_with_residual(const BrcMatrix& a, const Eigen::VectorXd& b,
                                                       Eigen::VectorXd& x,
                                                       Eigen::VectorXd& r) const {
  sweep_from_zero(a, b, x, &r);
}

void BlockGaussSeidel::sweep_from_zero(const BrcMatrix& a, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, Eigen::VectorXd* r) const {
  x.resize(b.size());
  const bool hybrid = ordering_ == SmootherOrdering::Hybrid;
  if (!hybrid && ordering_ != SmootherOrdering::Sequential) {
    x.setZero();
    forward(a, b, x);
    if (r) a.residual(b, x, *r);
    return;
  }
  // From x = 0 a row reads only the values this sweep already wrote: its own domain's columns
  // below the diagonal (every other term multiplies a zero), so half the matrix is read.
  if (r) r->resize(b.size());
  double* xs = x.data();
  double* rs = r ? r->data() : nullptr;
  const int* col = a.col_index.data();
  const double* v = a.values.data();
  const int domains = hybrid ? num_domains() : 1;
#pragma omp parallel num_threads(std::min(domains, threads_for(a.num_blocks(), LoopItems::Blocks)))
  {
#pragma omp for schedule(static)  // contiguous runs of domains, as in sweep_hybrid
    for (int d = 0; d < domains; ++d) {
      const int first = hybrid ? domain_start_[d] : 0,
                last = hybrid ? domain_start_[d + 1] : a.block_rows;
      for (int i = first; i < last; ++i) {
        const int begin = hybrid ? own_begin_[i] : a.row_start[i], diagonal = diagonal_block_[i];
        double fresh[3];
        block_row_sum<false, true>(
            col, v, begin, diagonal, [xs](int j) { return xs + 3 * j; }, fresh);
        const double ri[3] = {b[3 * i] - fresh[0], b[3 * i + 1] - fresh[1],
                              b[3 * i + 2] - fresh[2]};
        double* xi = xs + 3 * i;
        solve_diagonal(inverse_diagonal_[i].data(), ri, xi);
        if (!rs) continue;
        // The row now leaves b_i - (the blocks read and A_ii) x = (M_ii - A_ii) x_i: the l1
        // term, 0 for the sequential ordering. The same blocks, transposed, are the domain's
        // blocks right of the diagonal in rows j < i (A symmetric): their term - A_ji x_i of
        // r_j, added now.
        for (int c = 0; c < 3; ++c) rs[3 * i + c] = hybrid ? l1_[3 * i + c] * xi[c] : 0.0;
        const double minus_xi[3] = {-xi[0], -xi[1], -xi[2]};
        add_transposed_row(col, v, begin, diagonal, minus_xi, rs);
      }
    }
    if (rs && hybrid) subtract_off_domain_products(a, xs, rs);
  }
}

void BlockGaussSeidel::subtract_off_domain_products(const BrcMatrix& a, const double* x,
                                                    double* r) const {
  // Called inside a parallel region, after the domains: every x is final once all have passed
  // the loop's barrier. Each halo row is written by one thread, its two runs summed in order.
  const int rows = static_cast<int>(halo_rows_.size());
  auto source = [x](int j) { return x + 3 * j; };
#pragma omp for schedule(static)
  for (int n = 0; n < rows; ++n) {
    const int i = halo_rows_[n];
    double left[3] = {0, 0, 0}, right[3] = {0, 0, 0};
    block_row_sum(a.col_index.data(), a.values.data(), a.row_start[i], own_begin_[i], source, left);
    block_row_sum(a.col_index.data(), a.values.data(), own_end_[i], a.row_start[i + 1], source,
                  right);
    for (int c = 0; c < 3; ++c) r[3 * i + c] -= left[c] + right[c];
  }
}

void BlockGaussSeidel::sweep_hybrid(const BrcMatrix& a, const Eigen::VectorXd& b,
                                    Eigen::VectorXd& x, bool forward) const {
  // frozen_: what the other domains read while this one changes. Each thread copies the rows of
  // the domains it then sweeps, and the domains go to the threads in contiguous runs, as the
  // rows of every other pass over x do (schedule(static)): a copy on one thread, or domains
  // dealt out one by one, left a thread's rows in the other core's cache, and the sweep waited
  // on the transfers (lib/docs/threads.md).
  const int domains = num_domains();
  if (domains > 1) frozen_.resize(x.size());
#pragma omp parallel num_threads(std::min(domains, threads_for(a.num_blocks(), LoopItems::Blocks)))
  {
    if (domains > 1) {
#pragma omp for schedule(static)
      for (int d = 0; d < domains; ++d) {
        const int first = 3 * domain_start_[d], size = 3 * domain_start_[d + 1] - first;
        frozen_.segment(first, size) = x.segment(first, size);
      }
    }
#pragma omp for schedule(static)
    for (int d = 0; d < domains; ++d) {
      if (forward)
        for (int i = domain_start_[d]; i < domain_start_[d + 1]; ++i)
          relax_row<true, false>(a, b, x, i, domain_start_[d], domain_start_[d + 1]);
      else
        for (int i = domain_start_[d + 1] - 1; i >= domain_start_[d]; --i)
          relax_row<true, true>(a, b, x, i, domain_start_[d], domain_start_[d + 1]);
    }
  }
}

void BlockGaussSeidel::sweep_domains(const BrcMatrix& a, const Eigen::VectorXd& b,
                                     Eigen::VectorXd& x, bool forward) const {
  // Interior rows read only their own domain (its boundary rows keep their values meanwhile).
  const int domains = num_domains();
#pragma omp parallel for schedule(static, 1) \
    num_threads(std::min(domains, threads_for(a.block_rows)))
  for (int d = 0; d < domains; ++d) {
    if (forward)
      for (int n = domain_start_[d]; n < domain_start_[d + 1]; ++n)
        relax_row<false, false>(a, b, x, domain_rows_[n], 0, 0);
    else
      for (int n = domain_start_[d + 1] - 1; n >= domain_start_[d]; --n)
        relax_row<false, true>(a, b, x, domain_rows_[n], 0, 0);
  }
}

void BlockGaussSeidel::sweep_colour(const BrcMatrix& a, const Eigen::VectorXd& b,
                                    Eigen::VectorXd& x, int colour) const {
  const int first = colour_start_[colour], last = colour_start_[colour + 1];
#pragma omp parallel for schedule(static) num_threads(threads_for(last - first))
  for (int n = first; n < last; ++n) relax_row<false, false>(a, b, x, colour_rows_[n], 0, 0);
}

void BlockGaussSeidel::forward(const BrcMatrix& a, const Eigen::VectorXd& b,
                               Eigen::VectorXd& x) const {
  if (ordering_ == SmootherOrdering::Hybrid) return sweep_hybrid(a, b, x, true);
  if (ordering_ == SmootherOrdering::Domains) sweep_domains(a, b, x, true);
  if (ordering_ != SmootherOrdering::Sequential) {
    for (int c = 0; c < num_colours(); ++c) sweep_colour(a, b, x, c);
    return;
  }
  for (int i = 0; i < a.block_rows; ++i) relax_row<false, false>(a, b, x, i, 0, 0);
}

void BlockGaussSeidel::backward(const BrcMatrix& a, const Eigen::VectorXd& b,
                                Eigen::VectorXd& x) const {
  if (ordering_ == SmootherOrdering::Hybrid) return sweep_hybrid(a, b, x, false);
  if (ordering_ != SmootherOrdering::Sequential) {
    for (int c = num_colours() - 1; c >= 0; --c) sweep_colour(a, b, x, c);
    if (ordering_ == SmootherOrdering::Domains) sweep_domains(a, b, x, false);
    return;
  }
  for (int i = a.block_rows - 1; i >= 0; --i) relax_row<false, true>(a, b, x, i, 0, 0);
}

void BlockGaussSeidel::block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  const int n = static_cast<int>(inverse_diagonal_.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (int i = 0; i < n; ++i)
    solve_diagonal(inverse_diagonal_[i].data(), r.data() + 3 * i, z.data() + 3 * i);
}

}  // namespace corofem
