#pragma once
// A BRC matrix as an Eigen compressed-column matrix, for CHOLMOD and for oracle comparisons.
// The pattern and the value permutation are built once; update() only copies values.
#include <Eigen/SparseCore>

#include "sparse/brc_matrix.hpp"

namespace corofem {

class BrcToEigen {
 public:
  /// Full: every entry. SymmetricUpper: the upper triangle of a symmetric A, taken from its lower
  /// triangle by rows (column n holds row n's entries left of and on the diagonal), so that
  /// update() reads A's values in storage order; what a solver that reads one triangle needs.
  enum class Part { Full, SymmetricUpper };

  explicit BrcToEigen(const BrcMatrix& pattern, Part part = Part::Full);
  /// Copies A's values (A has the pattern given at construction) into matrix().
  void update(const BrcMatrix& a);
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> source_;  ///< BRC value index of every Eigen value, in Eigen's order
};

/// One-off conversion (tests, exports).
Eigen::SparseMatrix<double> to_eigen(const BrcMatrix& a);

}  // namespace corofem
