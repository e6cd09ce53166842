#include "cholmod_oracle.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>

namespace corofem::reference {

Eigen::VectorXd cholmod_solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b) {
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> factor;  // CHOLMOD_AUTO
  factor.cholmod().print = 0;  // a failure is the exception below
  factor.compute(a);
  if (factor.info() != Eigen::Success)
    throw std::runtime_error("CHOLMOD oracle: factorization failed");
  Eigen::VectorXd x = factor.solve(b);
  if (factor.info() != Eigen::Success) throw std::runtime_error("CHOLMOD oracle: solve failed");
  return x;
}

}  // namespace corofem::reference
