#include "multigrid/gauss_seidel.hpp"

#include <Eigen/LU>
#include <algorithm>

#include "core/errors.hpp"
#include "core/threads.hpp"

namespace corofem {

SmootherOrdering smoother_ordering(const std::string& name) {
  if (name == "sequential") return SmootherOrdering::Sequential;
  if (name == "multicolour") return SmootherOrdering::Multicolour;
  if (name == "domains") return SmootherOrdering::Domains;
  if (name == "hybrid") return SmootherOrdering::Hybrid;
  throw InputError("analysis.smoother: unknown ordering '" + name +
                   "' (known: sequential, multicolour, domains, hybrid)");
}

const char* smoother_ordering_name(SmootherOrdering ordering) {
  switch (ordering) {
    case SmootherOrdering::Multicolour: return "multicolour";
    case SmootherOrdering::Domains: return "domains";
    case SmootherOrdering::Hybrid: return "hybrid";
    default: return "sequential";
  }
}

namespace {

/// Greedy colouring of the rows `which` (ascending) in the block graph: each takes the smallest
/// colour none of its neighbours among them has. Returns them grouped by colour (ascending within).
void colour_rows(const BrcMatrix& a, const std::vector<int>& which, std::vector<int>& start, std::vector<int>& rows) {
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
  diagonal_block_.resize(a.block_rows);
  int missing = 0;  // no exception may leave a parallel region: counted, thrown after it
#pragma omp parallel for schedule(static) reduction(+ : missing) num_threads(threads_for(a.block_rows))
  for (int i = 0; i < a.block_rows; ++i) {
    diagonal_block_[i] = a.find(i, i);
    if (diagonal_block_[i] < 0) {
      ++missing;
      continue;
    }
    Eigen::Matrix3d d = a.block(diagonal_block_[i]);
    if (hybrid) {  // the l1 norm of the off-domain entries, row by row
      Eigen::Vector3d l1 = Eigen::Vector3d::Zero();
      for (int k = a.row_start[i]; k < own_begin_[i]; ++k) l1 += a.block(k).cwiseAbs().rowwise().sum();
      for (int k = own_end_[i]; k < a.row_start[i + 1]; ++k) l1 += a.block(k).cwiseAbs().rowwise().sum();
      l1_[i] = l1;
      d.diagonal() += l1;
    }
    inverse_diagonal_[i] = d.inverse();
  }
  if (missing > 0) throw NumericalFault("multigrid: a level has no diagonal block");
}

void BlockGaussSeidel::order_rows(const BrcMatrix& a) {
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
  // An even count (when more than one) balances two threads; never the thread count itself.
  int domains = std::max(1, static_cast<int>(a.col_index.size() / domain_size_));
  if (domains > 1 && domains % 2 == 1) ++domains;
  std::vector<long long> prefix(a.row_start.begin(), a.row_start.end());
  domain_start_ = balanced_ranges(prefix, domains);
  own_begin_.resize(a.block_rows);
  own_end_.resize(a.block_rows);
  l1_.assign(a.block_rows, Eigen::Vector3d::Zero());
  boundary_rows_ = 0;
  for (int d = 0; d < domains; ++d) {
    const int lo = domain_start_[d], hi = domain_start_[d + 1];
    for (int i = lo; i < hi; ++i) {
      const auto first = a.col_index.begin() + a.row_start[i], last = a.col_index.begin() + a.row_start[i + 1];
      own_begin_[i] = static_cast<int>(std::lower_bound(first, last, lo) - a.col_index.begin());
      own_end_[i] = static_cast<int>(std::lower_bound(first, last, hi) - a.col_index.begin());
      boundary_rows_ += own_begin_[i] != a.row_start[i] || own_end_[i] != a.row_start[i + 1];
    }
  }
}

void BlockGaussSeidel::relax_hybrid(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                    int i) const {
  // (D + D_l1) x_i = b_i + D_l1 x_i - sum_{own j != i} A_ij x_j - sum_{other j} A_ij frozen_j
  Eigen::Vector3d r = b.segment<3>(3 * i) + l1_[i].cwiseProduct(x.segment<3>(3 * i));
  for (int k = a.row_start[i]; k < own_begin_[i]; ++k)
    r.noalias() -= a.block(k) * frozen_.segment<3>(3 * a.col_index[k]);
  for (int k = own_begin_[i]; k < own_end_[i]; ++k)
    if (k != diagonal_block_[i]) r.noalias() -= a.block(k) * x.segment<3>(3 * a.col_index[k]);
  for (int k = own_end_[i]; k < a.row_start[i + 1]; ++k)
    r.noalias() -= a.block(k) * frozen_.segment<3>(3 * a.col_index[k]);
  x.segment<3>(3 * i) = inverse_diagonal_[i] * r;
}

void BlockGaussSeidel::sweep_hybrid(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                    bool forward) const {
  const int domains = num_domains();
  if (domains > 1) frozen_ = x;  // what the other domains read while this one changes
#pragma omp parallel for schedule(static, 1) num_threads(std::min(domains, threads_for(a.num_blocks())))
  for (int d = 0; d < domains; ++d) {
    if (forward)
      for (int i = domain_start_[d]; i < domain_start_[d + 1]; ++i) relax_hybrid(a, b, x, i);
    else
      for (int i = domain_start_[d + 1] - 1; i >= domain_start_[d]; --i) relax_hybrid(a, b, x, i);
  }
}

void BlockGaussSeidel::sweep_domains(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                     bool forward) const {
  // Interior rows read only their own domain (its boundary rows keep their values meanwhile).
  const int domains = num_domains();
#pragma omp parallel for schedule(static, 1) num_threads(std::min(domains, threads_for(a.block_rows)))
  for (int d = 0; d < domains; ++d) {
    if (forward)
      for (int n = domain_start_[d]; n < domain_start_[d + 1]; ++n) relax(a, b, x, domain_rows_[n]);
    else
      for (int n = domain_start_[d + 1] - 1; n >= domain_start_[d]; --n) relax(a, b, x, domain_rows_[n]);
  }
}

void BlockGaussSeidel::relax(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             int i) const {
  Eigen::Vector3d r = b.segment<3>(3 * i);
  for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
    if (k != diagonal_block_[i]) r.noalias() -= a.block(k) * x.segment<3>(3 * a.col_index[k]);
  x.segment<3>(3 * i) = inverse_diagonal_[i] * r;
}

void BlockGaussSeidel::sweep_colour(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                    int colour) const {
  const int first = colour_start_[colour], last = colour_start_[colour + 1];
#pragma omp parallel for schedule(static) num_threads(threads_for(last - first))
  for (int n = first; n < last; ++n) relax(a, b, x, colour_rows_[n]);
}

void BlockGaussSeidel::forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (ordering_ == SmootherOrdering::Hybrid) return sweep_hybrid(a, b, x, true);
  if (ordering_ == SmootherOrdering::Domains) sweep_domains(a, b, x, true);
  if (ordering_ != SmootherOrdering::Sequential) {
    for (int c = 0; c < num_colours(); ++c) sweep_colour(a, b, x, c);
    return;
  }
  for (int i = 0; i < a.block_rows; ++i) relax(a, b, x, i);
}

void BlockGaussSeidel::backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (ordering_ == SmootherOrdering::Hybrid) return sweep_hybrid(a, b, x, false);
  if (ordering_ != SmootherOrdering::Sequential) {
    for (int c = num_colours() - 1; c >= 0; --c) sweep_colour(a, b, x, c);
    if (ordering_ == SmootherOrdering::Domains) sweep_domains(a, b, x, false);
    return;
  }
  for (int i = a.block_rows - 1; i >= 0; --i) relax(a, b, x, i);
}

void BlockGaussSeidel::block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  const int n = static_cast<int>(inverse_diagonal_.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (int i = 0; i < n; ++i) z.segment<3>(3 * i) = inverse_diagonal_[i] * r.segment<3>(3 * i);
}

}  // namespace corofem
