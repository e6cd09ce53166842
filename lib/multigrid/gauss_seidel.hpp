#pragma once
// Nodal 3x3-block Gauss-Seidel: x_i <- D_ii^{-1} (b_i - sum_{j != i} A_ij x_j), vertex by vertex.
// Forward then backward sweeps make the V-cycle a symmetric preconditioner for CG.
#include <Eigen/Core>
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

class BlockGaussSeidel {
 public:
  /// Inverts the diagonal blocks of A (recompute whenever A's values change).
  void set_matrix(const BrcMatrix& a);
  void forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  void backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// z = D^{-1} r with the same inverted diagonal blocks (the block-Jacobi preconditioner).
  void block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

 private:
  void relax(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int i) const;
  std::vector<Eigen::Matrix3d> inverse_diagonal_;
  std::vector<int> diagonal_block_;
};

}  // namespace corofem
