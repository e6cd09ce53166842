#pragma once
// The start of a step's iterative solve from the solutions of the steps before it (Fischer 1998,
// "Projection techniques for iterative solution of Ax = b with successive right-hand sides"):
// of all x in span{x_n, ..., x_{n-K+1}}, the one nearest the solution in the A-norm,
// x0 = V y with (V^T A V) y = V^T b, V those solutions. The span holds the
// linear extrapolation 2 x_n - x_{n-1}, so x0's A-norm error is never larger than the
// extrapolation's; its price is K products with A a step (A changes every step).
#include <Eigen/Core>
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

class ProjectedStart {
 public:
  /// `history`: K, the solutions kept (at least 2, so that the span holds the extrapolation).
  explicit ProjectedStart(int history);
  /// Keeps `latest` (the last step's solution) among the K most recent, then writes the
  /// projection for A x = b into `start`. False, `start` untouched, when the kept solutions span
  /// nothing (all zero) or V^T A V is not positive semi-definite (A not SPD on the span).
  bool compute(const BrcMatrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& latest,
               Eigen::VectorXd& start);

 private:
  int history_;
  std::vector<Eigen::VectorXd> solutions_;  ///< the most recent first
  std::vector<Eigen::VectorXd> products_;   ///< A times each of them
};

}  // namespace corofem
