#include "multigrid/gauss_seidel.hpp"

#include <Eigen/LU>

#include "core/errors.hpp"

namespace corofem {

void BlockGaussSeidel::set_matrix(const BrcMatrix& a) {
  inverse_diagonal_.resize(a.block_rows);
  diagonal_block_.resize(a.block_rows);
  for (int i = 0; i < a.block_rows; ++i) {
    diagonal_block_[i] = a.find(i, i);
    if (diagonal_block_[i] < 0) throw NumericalFault("multigrid: a level has no diagonal block");
    inverse_diagonal_[i] = Eigen::Matrix3d(a.block(diagonal_block_[i])).inverse();
  }
}

void BlockGaussSeidel::relax(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             int i) const {
  Eigen::Vector3d r = b.segment<3>(3 * i);
  for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
    if (k != diagonal_block_[i]) r.noalias() -= a.block(k) * x.segment<3>(3 * a.col_index[k]);
  x.segment<3>(3 * i) = inverse_diagonal_[i] * r;
}

void BlockGaussSeidel::forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  for (int i = 0; i < a.block_rows; ++i) relax(a, b, x, i);
}

void BlockGaussSeidel::backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  for (int i = a.block_rows - 1; i >= 0; --i) relax(a, b, x, i);
}

void BlockGaussSeidel::block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  for (std::size_t i = 0; i < inverse_diagonal_.size(); ++i)
    z.segment<3>(3 * i) = inverse_diagonal_[i] * r.segment<3>(3 * i);
}

}  // namespace corofem
