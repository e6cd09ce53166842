#include "linalg/projected_start.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace corofem {

namespace {

/// Directions of the span whose energy is below this fraction of the largest's (successive
/// velocities are nearly parallel) are left out: round-off would decide their coefficients.
constexpr double kEnergyCutoff = 1e-12;

}  // namespace

ProjectedStart::ProjectedStart(int history) : history_(history) {
  if (history < 2) throw std::invalid_argument("ProjectedStart: history must be at least 2");
}

bool ProjectedStart::compute(const BrcMatrix& a, const Eigen::VectorXd& b,
                             const Eigen::VectorXd& latest, Eigen::VectorXd& start) {
  // Keep the newest K; the oldest vector's storage is reused for the newest.
  if (static_cast<int>(solutions_.size()) < history_) solutions_.emplace_back();
  std::rotate(solutions_.rbegin(), solutions_.rbegin() + 1, solutions_.rend());
  solutions_.front() = latest;

  // The Galerkin system on the span, in the kept solutions V themselves: (V^T A V) y = V^T b. V's
  // columns are nearly dependent, so it is solved in the eigenvectors of its Gram matrix scaled to
  // a unit diagonal, the weakest directions dropped (a pseudo-inverse: the least-A-norm-error start
  // on the span the round-off resolves).
  products_.resize(solutions_.size());
  for (std::size_t i = 0; i < solutions_.size(); ++i) a.multiply(solutions_[i], products_[i]);
  const int k = static_cast<int>(solutions_.size());
  Eigen::MatrixXd gram(k, k);
  Eigen::VectorXd projected_b(k), scale(k);
  for (int i = 0; i < k; ++i) {
    projected_b[i] = solutions_[i].dot(b);
    for (int j = 0; j <= i; ++j)  // A symmetric: the mean of the two round-offs
      gram(i, j) = gram(j, i) =
          0.5 * (solutions_[i].dot(products_[j]) + solutions_[j].dot(products_[i]));
    // a zero (or, A not SPD, negative) energy: the solution is left out
    scale[i] = gram(i, i) > 0 ? 1 / std::sqrt(gram(i, i)) : 0.0;
  }
  if (!(scale.maxCoeff() > 0)) return false;
  const Eigen::MatrixXd scaled = scale.asDiagonal() * gram * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  if (eigen.info() != Eigen::Success) return false;
  const Eigen::VectorXd& energy = eigen.eigenvalues();                       // ascending
  if (energy.minCoeff() < -kEnergyCutoff * energy.maxCoeff()) return false;  // A not SPD on V
  const Eigen::VectorXd scaled_b = scale.cwiseProduct(projected_b);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(k);
  for (int m = 0; m < k; ++m)
    if (energy[m] > kEnergyCutoff * energy.maxCoeff())
      y += (eigen.eigenvectors().col(m).dot(scaled_b) / energy[m]) * eigen.eigenvectors().col(m);
  y = scale.cwiseProduct(y);
  if (!y.allFinite()) return false;
  start = y[0] * solutions_[0];
  for (int i = 1; i < k; ++i) start += y[i] * solutions_[i];
  return true;
}

}  // namespace corofem
