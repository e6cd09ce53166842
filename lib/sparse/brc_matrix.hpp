#pragma once
// Block-row-compressed matrix (paper 4.1): CSR whose entries are dense 3x3 blocks, one block per
// vertex pair; blocks stored row-major, 9 doubles each, in row order with sorted columns.
#include <Eigen/Core>
#include <vector>

namespace corofem {

struct BrcMatrix {
  using Block = Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
  using ConstBlock = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;

  int block_rows = 0;
  int block_cols = 0;
  std::vector<int> row_start;  ///< block_rows + 1 offsets into col_index
  std::vector<int> col_index;  ///< block column of every block, sorted within a row
  std::vector<double> values;  ///< 9 per block

  int num_blocks() const { return static_cast<int>(col_index.size()); }
  Block block(int k) { return Block(values.data() + 9 * k); }
  ConstBlock block(int k) const { return ConstBlock(values.data() + 9 * k); }
  /// Index of block (i, j), or -1 if (i, j) is not in the pattern (binary search in row i).
  int find(int i, int j) const;
  void set_zero();
  /// y = A x (sizes 3*block_cols and 3*block_rows).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// r = b - A x in the product's pass (threaded as multiply(): the same bits at every count).
  void residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const;
  Eigen::VectorXd operator*(const Eigen::VectorXd& x) const;
};

/// Pattern (values zero) from sorted, duplicate-free column lists per block row.
BrcMatrix make_brc_pattern(int block_cols, const std::vector<std::vector<int>>& columns_per_row);

}  // namespace corofem
