#pragma once
// The direct-solve oracle: A x = b by CHOLMOD through Eigen's wrapper on the lower triangle,
// analysed and factorized afresh at every call, with CHOLMOD's defaults (it picks a simplicial
// LDL^T for a small matrix, a supernodal LL^T where the flops per entry of the factor make that
// pay). Deliberately a different path from the production factorization
// (linalg/cholmod_factorization.hpp: our wrapper, upper triangle, analysis kept and reused), so
// that a fault there does not hide in the oracle; the numeric kernel they may share is CHOLMOD's.
// Always simplicial, each of the report's checked steps on quadruped-67k took about 8 s
// (cholmod_rowfac); Table 1's main run there went from 37 to 10 s with this and the mesh kept.
#include <Eigen/SparseCore>

namespace corofem::reference {

/// x with A x = b, A symmetric positive definite; std::runtime_error when the factorization fails.
Eigen::VectorXd cholmod_solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b);

}  // namespace corofem::reference
