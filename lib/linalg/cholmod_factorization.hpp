#pragma once
// Direct sparse Cholesky LL^T by CHOLMOD (through Eigen's CholmodSupport), for the production path:
// the multigrid's coarsest level, the `cholmod` solver and Newton's tangent. The analysis is kept
// for the pattern, only the upper triangle is read, and CHOLMOD's own OpenMP stays serial.
// (The oracle the tests check solves against is reference/cholmod_oracle.hpp, a separate path.)
#include <Eigen/SparseCore>
#include <memory>

#include "linalg/factorization_kind.hpp"

namespace corofem {

class CholmodFactorization {
 public:
  explicit CholmodFactorization(Factorization kind = Factorization::Supernodal);
  ~CholmodFactorization();
  CholmodFactorization(CholmodFactorization&&) noexcept;
  CholmodFactorization& operator=(CholmodFactorization&&) noexcept;

  /// Symbolic analysis (fill-reducing ordering); needed once per pattern.
  void analyze(const Eigen::SparseMatrix<double>& a);
  /// Numeric factorization of a symmetric positive definite A with the analyzed pattern; only the
  /// upper triangle is read. Throws std::runtime_error if A is not positive definite.
  void factorize(const Eigen::SparseMatrix<double>& a);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Entries of the factor L and flops of one numeric factorization, as CHOLMOD's analysis
  /// counted them (0 before analyze()).
  double factor_nonzeros() const;
  double factorization_flops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace corofem
