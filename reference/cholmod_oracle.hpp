#pragma once
// The direct-solve oracle: A x = b by CHOLMOD's simplicial LDL^T on the whole matrix, analysed and
// factorized afresh at every call, with CHOLMOD's defaults. Deliberately a different path from
// the production factorization (linalg/cholmod_factorization.hpp: supernodal, upper triangle,
// analysis kept), so that a fault there does not hide in the oracle.
#include <Eigen/SparseCore>

namespace corofem::reference {

/// x with A x = b, A symmetric positive definite; std::runtime_error when the factorization fails.
Eigen::VectorXd cholmod_solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b);

}  // namespace corofem::reference
