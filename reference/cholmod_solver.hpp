#pragma once
// Direct sparse Cholesky by CHOLMOD (through Eigen's CholmodSupport): the oracle every iterative
// solve is checked against, and the coarsest-level solver of multigrid.
#include <Eigen/SparseCore>
#include <memory>

namespace corofem::reference {

class CholmodSolver {
 public:
  CholmodSolver();
  ~CholmodSolver();
  CholmodSolver(CholmodSolver&&) noexcept;
  CholmodSolver& operator=(CholmodSolver&&) noexcept;

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

/// One-shot solve of A x = b (A symmetric positive definite).
Eigen::VectorXd cholmod_solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b);

}  // namespace corofem::reference
