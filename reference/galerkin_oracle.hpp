#pragma once
// Oracles of the Galerkin product E = R A R^T: a dense product for small sizes and Eigen's sparse
// product; both written as plainly as the formula (AMGCL's product(R, product(A, P)) shape).
#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace corofem::reference {

Eigen::MatrixXd dense_galerkin(const Eigen::MatrixXd& r, const Eigen::MatrixXd& a);

Eigen::SparseMatrix<double> eigen_galerkin(const Eigen::SparseMatrix<double>& r,
                                           const Eigen::SparseMatrix<double>& a);

}  // namespace corofem::reference
