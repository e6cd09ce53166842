#include "sparse/brc_to_eigen.hpp"

namespace corofem {

BrcToEigen::BrcToEigen(const BrcMatrix& pattern) {
  // Tag each value with its BRC position, let Eigen sort into columns, then read the tags back.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(pattern.values.size());
  for (int i = 0; i < pattern.block_rows; ++i)
    for (int k = pattern.row_start[i]; k < pattern.row_start[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          triplets.emplace_back(3 * i + r, 3 * pattern.col_index[k] + c, 9.0 * k + 3 * r + c);
  matrix_.resize(3 * pattern.block_rows, 3 * pattern.block_cols);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  destination_.resize(pattern.values.size());
  for (int n = 0; n < matrix_.nonZeros(); ++n)
    destination_[static_cast<std::size_t>(matrix_.valuePtr()[n])] = n;
  update(pattern);
}

void BrcToEigen::update(const BrcMatrix& a) {
  double* dst = matrix_.valuePtr();
  for (std::size_t n = 0; n < destination_.size(); ++n) dst[destination_[n]] = a.values[n];
}

Eigen::SparseMatrix<double> to_eigen(const BrcMatrix& a) { return BrcToEigen(a).matrix(); }

}  // namespace corofem
