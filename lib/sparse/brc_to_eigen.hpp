#pragma once
// A BRC matrix as an Eigen compressed-column matrix, for CHOLMOD and for oracle comparisons.
// The pattern and the value permutation are built once; update() only copies values.
#include <Eigen/SparseCore>

#include "sparse/brc_matrix.hpp"

namespace corofem {

class BrcToEigen {
 public:
  explicit BrcToEigen(const BrcMatrix& pattern);
  /// Copies A's values (A has the pattern given at construction) into matrix().
  void update(const BrcMatrix& a);
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> destination_;  ///< Eigen value index of every BRC value
};

/// One-off conversion (tests, exports).
Eigen::SparseMatrix<double> to_eigen(const BrcMatrix& a);

}  // namespace corofem
