#include "sparse/brc_to_eigen.hpp"

namespace corofem {

BrcToEigen::BrcToEigen(const BrcMatrix& pattern, Part part) {
  // Tag each value with its BRC position, let Eigen sort into columns, then read the tags back.
  const bool upper = part == Part::SymmetricUpper;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(upper ? pattern.values.size() / 2 + 3 * pattern.block_rows
                         : pattern.values.size());
  for (int i = 0; i < pattern.block_rows; ++i)
    for (int k = pattern.row_start[i]; k < pattern.row_start[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const int row = 3 * i + r, col = 3 * pattern.col_index[k] + c;
          const double tag = 9.0 * k + 3 * r + c;
          if (!upper)
            triplets.emplace_back(row, col, tag);
          else if (col <= row)
            triplets.emplace_back(col, row, tag);  // A(row, col) = A(col, row), above the diagonal
        }
  matrix_.resize(3 * pattern.block_rows, 3 * pattern.block_cols);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  source_.resize(static_cast<std::size_t>(matrix_.nonZeros()));
  for (std::size_t n = 0; n < source_.size(); ++n)
    source_[n] = static_cast<int>(matrix_.valuePtr()[n]);
  update(pattern);
}

void BrcToEigen::update(const BrcMatrix& a) {
  double* dst = matrix_.valuePtr();
  for (std::size_t n = 0; n < source_.size(); ++n) dst[n] = a.values[source_[n]];
}

Eigen::SparseMatrix<double> to_eigen(const BrcMatrix& a) {
  return BrcToEigen(a).matrix();
}

}  // namespace corofem
