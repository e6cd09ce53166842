#include "linalg/chebyshev_smoother.hpp"

#include <Eigen/Dense>

#include "core/errors.hpp"
#include "core/threads.hpp"

namespace corofem {

std::vector<Eigen::Matrix3d> l1_block_diagonal_inverse(const BrcMatrix& a) {
  std::vector<Eigen::Matrix3d> inverse(a.block_rows);
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
    inverse[i] = d.inverse();
  }
  if (missing_diagonal) throw NumericalFault("multigrid: a level has no diagonal block");
  return inverse;
}

void ChebyshevSmoother::set_matrix(const BrcMatrix& a) {
  inverse_ = l1_block_diagonal_inverse(a);
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

bool ChebyshevSmoother::pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                   int sweeps, bool zero_guess, Eigen::VectorXd&) const {
  for (int s = 0; s < sweeps; ++s) smooth(a, b, x, zero_guess && s == 0);
  if (sweeps == 0 && zero_guess) x.setZero(b.size());
  return false;
}

void ChebyshevSmoother::post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b,
                                    Eigen::VectorXd& x, int sweeps) const {
  for (int s = 0; s < sweeps; ++s) smooth(a, b, x, false);
}

Traffic ChebyshevSmoother::setup_traffic(const BrcMatrix& a) const {
  // Every block read (the off-diagonal ones' row sums: 18 flops each), the inverse written.
  const double rows = a.block_rows;
  return {matrix_bytes(a) + kBlockBytes * rows,
          18.0 * static_cast<double>(a.col_index.size()) + 50 * rows};
}

Traffic ChebyshevSmoother::smoothing_traffic(const BrcMatrix& a, bool zero_guess) const {
  const double rows = a.block_rows, n = 3 * rows;
  const double blocks = static_cast<double>(a.col_index.size());
  // The start: x zeroed and r = b copied, or r = b - A x.
  Traffic out =
      zero_guess ? Traffic{24 * n, 0} : Traffic{matrix_bytes(a) + 24 * n, 18 * blocks + n};
  // The first step: z = M^-1 r, d = z / theta, x += d (M^-1 and r read, d written, x updated).
  out += {kBlockBytes * rows + 8 * n + 8 * n + 16 * n, 21 * rows};
  // Each further step: r - A d in the product's pass, then d = keep d + scale M^-1 r, x += d.
  const Traffic next = {matrix_bytes(a) + 24 * n + kBlockBytes * rows + 8 * n + 16 * n + 16 * n,
                        18 * blocks + n + 27 * rows};
  out += (degree_ - 1) * next;
  return out;
}

Traffic ChebyshevSmoother::pre_traffic(const BrcMatrix& a, int sweeps) const {
  if (sweeps == 0) return {};
  Traffic out = smoothing_traffic(a, true);
  out += (sweeps - 1) * smoothing_traffic(a, false);
  return out;
}

Traffic ChebyshevSmoother::post_traffic(const BrcMatrix& a, int sweeps) const {
  return sweeps * smoothing_traffic(a, false);
}

Parameters ChebyshevSmoother::describe() const {
  Parameters p;
  p.set("kind", std::string("chebyshev"));
  p.set("diagonal", std::string("l1 block Jacobi"));
  p.set("degree", static_cast<long long>(degree_));
  p.set("interval", std::vector<double>{lower_, 1.0});
  return p;
}

SmootherTraits chebyshev_smoother_traits() {
  return {.name = "chebyshev",
          .parameters = {{.key = "chebyshev_degree",
                          .kind = ParameterSpec::Kind::Integer,
                          .fallback = 2LL,
                          .min = 1,
                          .max = 16,
                          .meaning = "Chebyshev steps per smoothing"}},
          .make = [](const Parameters& p) {
            return std::unique_ptr<Smoother>(
                new ChebyshevSmoother(static_cast<int>(p.integer("chebyshev_degree"))));
          }};
}

}  // namespace corofem
