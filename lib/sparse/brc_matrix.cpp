#include "sparse/brc_matrix.hpp"

#include <algorithm>

#include "core/threads.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {

int BrcMatrix::find(int i, int j) const {
  auto first = col_index.begin() + row_start[i];
  auto last = col_index.begin() + row_start[i + 1];
  auto it = std::lower_bound(first, last, j);
  return (it != last && *it == j) ? static_cast<int>(it - col_index.begin()) : -1;
}

void BrcMatrix::set_zero() {
  std::fill(values.begin(), values.end(), 0.0);
}

void BrcMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(3 * block_rows);
  const double* xs = x.data();
  auto source = [xs](int j) { return xs + 3 * j; };
#pragma omp parallel for schedule(static) num_threads(threads_for(num_blocks(), LoopItems::Blocks))
  for (int i = 0; i < block_rows; ++i)
    block_row_sum(col_index.data(), values.data(), row_start[i], row_start[i + 1], source,
                  y.data() + 3 * i);
}

void BrcMatrix::residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x,
                         Eigen::VectorXd& r) const {
  r.resize(3 * block_rows);
  const double* xs = x.data();
  auto source = [xs](int j) { return xs + 3 * j; };
#pragma omp parallel for schedule(static) num_threads(threads_for(num_blocks(), LoopItems::Blocks))
  for (int i = 0; i < block_rows; ++i) {
    double s[3];
    block_row_sum(col_index.data(), values.data(), row_start[i], row_start[i + 1], source, s);
    for (int c = 0; c < 3; ++c) r[3 * i + c] = b[3 * i + c] - s[c];
  }
}

Eigen::VectorXd BrcMatrix::operator*(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y;
  multiply(x, y);
  return y;
}

BrcMatrix make_brc_pattern(int block_cols, const std::vector<std::vector<int>>& columns_per_row) {
  BrcMatrix m;
  m.block_rows = static_cast<int>(columns_per_row.size());
  m.block_cols = block_cols;
  m.row_start.reserve(m.block_rows + 1);
  m.row_start.push_back(0);
  for (const auto& cols : columns_per_row) {
    m.col_index.insert(m.col_index.end(), cols.begin(), cols.end());
    m.row_start.push_back(static_cast<int>(m.col_index.size()));
  }
  m.values.assign(9 * m.col_index.size(), 0.0);
  return m;
}

}  // namespace corofem
