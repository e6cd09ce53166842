#pragma once
// Nodal 3x3-block Gauss-Seidel: x_i <- D_ii^{-1} (b_i - sum_{j != i} A_ij x_j), vertex by vertex.
// Forward then backward sweeps make the V-cycle a symmetric preconditioner for CG.
// Three orderings, each a fixed order of the vertices whatever the thread count (so the same
// bits at every count), the backward sweep its exact reverse (so the pair stays symmetric):
//  - sequential: the vertices' own order, one thread;
//  - multicolour: vertices sharing no block get one colour and relax together on every thread;
//  - domains: the rows split into contiguous domains of about 4096 vertices (a count set by the
//    level's size, not by the threads); first every domain's interior vertices (no neighbour in
//    another domain) in their own order, the domains side by side on the threads, then the
//    vertices on domain boundaries by colours. On a locality-ordered mesh nearly every vertex is
//    interior, so this is nearly the sequential smoother, with its locality, on every thread.
// Their rho against each other: BM_MultigridQuality and verify/multigrid_solver_test.cpp.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

enum class SmootherOrdering { Sequential, Multicolour, Domains };
SmootherOrdering smoother_ordering(const std::string& name);  ///< "sequential" | "multicolour" | "domains"
const char* smoother_ordering_name(SmootherOrdering ordering);

class BlockGaussSeidel {
 public:
  /// `domain_rows`: the domains' size for the domains ordering.
  explicit BlockGaussSeidel(SmootherOrdering ordering = SmootherOrdering::Sequential, int domain_rows = 4096)
      : ordering_(ordering), domain_rows_target_(domain_rows) {}
  /// Inverts the diagonal blocks of A (recompute whenever A's values change); colours A's
  /// pattern the first time (multicolour).
  void set_matrix(const BrcMatrix& a);
  void forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  void backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// z = D^{-1} r with the same inverted diagonal blocks (the block-Jacobi preconditioner).
  void block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  int num_colours() const { return static_cast<int>(colour_start_.size()) - 1; }
  int num_domains() const { return static_cast<int>(domain_start_.size()) - 1; }
  /// Rows relaxed by colours (all of them for multicolour, the domain boundaries for domains).
  int coloured_rows() const { return static_cast<int>(colour_rows_.size()); }

 private:
  void relax(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int i) const;
  void sweep_colour(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int colour) const;
  void sweep_domains(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool forward) const;
  void order_rows(const BrcMatrix& a);
  SmootherOrdering ordering_;
  int domain_rows_target_;
  bool ordered_ = false;
  std::vector<Eigen::Matrix3d> inverse_diagonal_;
  std::vector<int> diagonal_block_;
  std::vector<int> colour_start_, colour_rows_;  ///< rows of each colour, ascending
  std::vector<int> domain_start_, domain_rows_;  ///< interior rows of each domain, ascending
};

}  // namespace corofem
