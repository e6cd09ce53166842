#include "linalg/chebyshev_smoother.hpp"

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "core/threads.hpp"

namespace corofem {

void ChebyshevSmoother::set_matrix(const BrcMatrix& a) {
  inverse_.resize(a.block_rows);
  bool missing_diagonal = false;
#pragma omp parallel for schedule(static) num_threads(threads_for(a.block_rows))
  for (int i = 0; i < a.block_rows; ++i) {
    Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
    Eigen::Vector3d l1 = Eigen::Vector3d::Zero();
    bool found = false;
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      if (a.col_index[k] == i) {
        d = a.block(k);
        found = true;
      } else {
        l1 += a.block(k).cwiseAbs().rowwise().sum();
      }
    }
    if (!found) missing_diagonal = true;
    d.diagonal() += l1;
    inverse_[i] = d.inverse();
  }
  if (missing_diagonal) throw NumericalFault("multigrid: a level has no diagonal block");
}

void ChebyshevSmoother::apply_inverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  const int n = static_cast<int>(inverse_.size());
  z.resize(3 * n);
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (int i = 0; i < n; ++i) z.segment<3>(3 * i) = inverse_[i] * r.segment<3>(3 * i);
}

void ChebyshevSmoother::smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                               bool zero_guess) const {
  // Saad, "Iterative Methods for Sparse Linear Systems", Algorithm 12.1 on [lower, 1]; each step's
  // vector updates in one row-parallel pass after the product.
  const double theta = (1 + lower_) / 2, delta = (1 - lower_) / 2, sigma = theta / delta;
  const int n = static_cast<int>(inverse_.size());
  if (zero_guess) {
    x.setZero(b.size());
    r_ = b;
  } else {
    a.residual(b, x, r_);
  }
  d_.resize(3 * n);
  const auto step = [&](double keep, double scale) {  // d = keep d + scale M^-1 r; x += d
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d z = inverse_[i] * r_.segment<3>(3 * i);
      const Eigen::Vector3d d = keep == 0
                                    ? Eigen::Vector3d(scale * z)  // d_ not yet set
                                    : Eigen::Vector3d(keep * d_.segment<3>(3 * i) + scale * z);
      d_.segment<3>(3 * i) = d;
      x.segment<3>(3 * i) += d;
    }
  };
  step(0.0, 1 / theta);
  double rho = 1 / sigma;
  for (int k = 1; k < degree_; ++k) {
    a.residual(r_, d_, ad_);  // r - A d in the product's pass
    r_.swap(ad_);
    const double rho_next = 1 / (2 * sigma - rho);
    step(rho_next * rho, 2 * rho_next / delta);
    rho = rho_next;
  }
}

}  // namespace corofem
