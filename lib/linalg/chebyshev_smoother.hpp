#pragma once
// Chebyshev polynomial smoothing on the l1 block-Jacobi diagonal (Adams,
// Brezina, Hu and Tuminaro 2003, "Parallel multigrid smoothing: polynomial versus Gauss-Seidel"):
// `degree` steps of the Chebyshev iteration for M^-1 A on the eigenvalue interval [lower, 1],
// M = blockdiag(A_ii + diag(l1 norms of row r's entries outside block i)). M - A is then
// symmetric and diagonally dominant, so positive semi-definite, and every eigenvalue of M^-1 A
// lies in (0, 1]: the upper bound needs no eigenvalue estimate, the smoother no set-up beyond M.
// A polynomial in M^-1 A, the same before and after the coarse correction, keeps the V-cycle a
// symmetric preconditioner. Reads the matrix as a product does (row-parallel, the same bits at
// every thread count), no ordering, no colours.
#include <Eigen/Core>
#include <vector>

#include "linalg/smoother.hpp"

namespace corofem {

/// M^-1 block by block, M = blockdiag(A_ii + diag(l1 norms of row r's entries outside block i)):
/// every eigenvalue of M^-1 A lies in (0, 1]. NumericalFault where a row has no diagonal block.
std::vector<Eigen::Matrix3d> l1_block_diagonal_inverse(const BrcMatrix& a);

class ChebyshevSmoother : public Smoother {
 public:
  /// `lower`: the interval's lower end; eigenvalues of M^-1 A below it (the smooth modes, left
  /// to the coarse correction) are damped little.
  explicit ChebyshevSmoother(int degree = 2, double lower = 0.1) : degree_(degree), lower_(lower) {}
  /// Inverts the l1-augmented diagonal blocks of A (recompute whenever A's values change).
  void set_matrix(const BrcMatrix& a) override;
  /// `degree` Chebyshev steps for A x = b from x (from x = 0 with `zero_guess`, whatever x holds).
  void smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
              bool zero_guess) const;
  /// As a multigrid smoother: `sweeps` smoothings, each of `degree` steps; the residual left to
  /// the caller.
  bool pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int sweeps,
                  bool zero_guess, Eigen::VectorXd& r) const override;
  bool forms_residual(int) const override { return false; }
  void post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   int sweeps) const override;
  Traffic setup_traffic(const BrcMatrix& a) const override;
  Traffic pre_traffic(const BrcMatrix& a, int sweeps) const override;
  Traffic post_traffic(const BrcMatrix& a, int sweeps) const override;
  Parameters describe() const override;
  /// z = M^{-1} r.
  void apply_inverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  int degree() const { return degree_; }
  double lower() const { return lower_; }

 private:
  /// One smooth(): from x = 0 or from x.
  Traffic smoothing_traffic(const BrcMatrix& a, bool zero_guess) const;
  int degree_;
  double lower_;
  std::vector<Eigen::Matrix3d> inverse_;
  mutable Eigen::VectorXd r_, d_, ad_;
};

/// The registration of "chebyshev" (linalg/smoother.hpp).
SmootherTraits chebyshev_smoother_traits();

}  // namespace corofem
