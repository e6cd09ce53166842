#pragma once
// Nodal 3x3-block Gauss-Seidel: x_i <- D_ii^{-1} (b_i - sum_{j != i} A_ij x_j), vertex by vertex.
// Forward then backward sweeps make the V-cycle a symmetric preconditioner for CG.
// Two orderings: the vertices' own (sequential, one thread) and multicolour, where vertices
// sharing no block get one colour and relax together on every thread; the backward sweep visits
// the colours in reverse, so the pair stays symmetric. Within a colour the relaxations do not
// read each other, so the multicolour result is bit-identical at every thread count; it is a
// different ordering from the sequential one (its rho is measured in BM_MultigridQuality).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

enum class SmootherOrdering { Sequential, Multicolour };
SmootherOrdering smoother_ordering(const std::string& name);  ///< "sequential" | "multicolour"
const char* smoother_ordering_name(SmootherOrdering ordering);

class BlockGaussSeidel {
 public:
  explicit BlockGaussSeidel(SmootherOrdering ordering = SmootherOrdering::Sequential) : ordering_(ordering) {}
  /// Inverts the diagonal blocks of A (recompute whenever A's values change); colours A's
  /// pattern the first time (multicolour).
  void set_matrix(const BrcMatrix& a);
  void forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  void backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// z = D^{-1} r with the same inverted diagonal blocks (the block-Jacobi preconditioner).
  void block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  int num_colours() const { return static_cast<int>(colour_start_.size()) - 1; }

 private:
  void relax(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int i) const;
  void sweep_colour(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int colour) const;
  SmootherOrdering ordering_;
  std::vector<Eigen::Matrix3d> inverse_diagonal_;
  std::vector<int> diagonal_block_;
  std::vector<int> colour_start_, colour_rows_;  ///< rows of each colour, ascending
};

}  // namespace corofem
