#include "cholmod_oracle.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>

namespace corofem::reference {

Eigen::VectorXd cholmod_solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b) {
  Eigen::CholmodSimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
  ldlt.cholmod().print = 0;  // a failure is the exception below
  ldlt.compute(a);
  if (ldlt.info() != Eigen::Success)
    throw std::runtime_error("CHOLMOD oracle: factorization failed");
  Eigen::VectorXd x = ldlt.solve(b);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("CHOLMOD oracle: solve failed");
  return x;
}

}  // namespace corofem::reference
