#include "galerkin_oracle.hpp"

namespace corofem::reference {

Eigen::MatrixXd dense_galerkin(const Eigen::MatrixXd& r, const Eigen::MatrixXd& a) {
  return r * a * r.transpose();
}

Eigen::SparseMatrix<double> eigen_galerkin(const Eigen::SparseMatrix<double>& r,
                                           const Eigen::SparseMatrix<double>& a) {
  const Eigen::SparseMatrix<double> ra = r * a;
  Eigen::SparseMatrix<double> e = ra * Eigen::SparseMatrix<double>(r.transpose());
  e.makeCompressed();
  return e;
}

}  // namespace corofem::reference
