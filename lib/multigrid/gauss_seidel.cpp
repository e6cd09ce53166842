#include "multigrid/gauss_seidel.hpp"

#include <Eigen/LU>

#include "core/errors.hpp"
#include "core/threads.hpp"

namespace corofem {

SmootherOrdering smoother_ordering(const std::string& name) {
  if (name == "sequential") return SmootherOrdering::Sequential;
  if (name == "multicolour") return SmootherOrdering::Multicolour;
  throw InputError("analysis.smoother: unknown ordering '" + name + "' (known: sequential, multicolour)");
}

const char* smoother_ordering_name(SmootherOrdering ordering) {
  return ordering == SmootherOrdering::Multicolour ? "multicolour" : "sequential";
}

namespace {

/// Greedy colouring of the block graph in row order: each row takes the smallest colour none of
/// its neighbours has. Returns the rows grouped by colour (ascending within a colour).
void colour_rows(const BrcMatrix& a, std::vector<int>& start, std::vector<int>& rows) {
  std::vector<int> colour(a.block_rows, -1), used;  // used[c] == i: colour c taken around row i
  int colours = 0;
  for (int i = 0; i < a.block_rows; ++i) {
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
  for (int c : colour) ++start[c + 1];
  for (int c = 0; c < colours; ++c) start[c + 1] += start[c];
  rows.resize(a.block_rows);
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int i = 0; i < a.block_rows; ++i) rows[next[colour[i]]++] = i;
}

}  // namespace

void BlockGaussSeidel::set_matrix(const BrcMatrix& a) {
  inverse_diagonal_.resize(a.block_rows);
  diagonal_block_.resize(a.block_rows);
  for (int i = 0; i < a.block_rows; ++i) {
    diagonal_block_[i] = a.find(i, i);
    if (diagonal_block_[i] < 0) throw NumericalFault("multigrid: a level has no diagonal block");
    inverse_diagonal_[i] = Eigen::Matrix3d(a.block(diagonal_block_[i])).inverse();
  }
  if (ordering_ == SmootherOrdering::Multicolour && colour_rows_.size() != static_cast<std::size_t>(a.block_rows))
    colour_rows(a, colour_start_, colour_rows_);
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
  if (ordering_ == SmootherOrdering::Multicolour) {
    for (int c = 0; c < num_colours(); ++c) sweep_colour(a, b, x, c);
    return;
  }
  for (int i = 0; i < a.block_rows; ++i) relax(a, b, x, i);
}

void BlockGaussSeidel::backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (ordering_ == SmootherOrdering::Multicolour) {
    for (int c = num_colours() - 1; c >= 0; --c) sweep_colour(a, b, x, c);
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
