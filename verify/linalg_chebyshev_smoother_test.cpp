// Chebyshev smoothing on the l1 block-Jacobi diagonal (linalg/chebyshev_smoother.hpp) against its
// analytic action: on an eigenvector v of M^-1 A with eigenvalue lambda, k steps from x = v for
// b = 0 leave q(lambda) v, q the scaled Chebyshev residual polynomial of [lower, 1].
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstring>
#include <random>

#include "core/threads.hpp"
#include "linalg/chebyshev_smoother.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// T_k(t), Chebyshev's polynomial of the first kind, for any real t.
double chebyshev_t(int k, double t) {
  double previous = 1, current = t;
  if (k == 0) return 1;
  for (int j = 1; j < k; ++j) {
    const double next = 2 * t * current - previous;
    previous = current;
    current = next;
  }
  return current;
}

/// The l1 block-Jacobi M of A, dense: the diagonal blocks plus, on each row's diagonal, the
/// absolute values of the row's entries outside its diagonal block.
Eigen::MatrixXd l1_block_diagonal(const BrcMatrix& a) {
  const Eigen::MatrixXd dense(to_eigen(a));
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(dense.rows(), dense.cols());
  for (int i = 0; i < a.block_rows; ++i) {
    m.block<3, 3>(3 * i, 3 * i) = dense.block<3, 3>(3 * i, 3 * i);
    for (int r = 3 * i; r < 3 * i + 3; ++r)
      m(r, r) += dense.row(r).cwiseAbs().sum() - dense.block(r, 3 * i, 1, 3).cwiseAbs().sum();
  }
  return m;
}

TEST(ChebyshevSmoother, ActsOnEachEigenvectorAsItsResidualPolynomial) {
  std::mt19937 rng(5);
  const BrcMatrix a = test::random_spd_brc(30, rng);
  const Eigen::MatrixXd dense(to_eigen(a));
  // A v = lambda M v.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, l1_block_diagonal(a));
  ASSERT_EQ(eig.info(), Eigen::Success);
  // The bound the smoother relies on instead of an eigenvalue estimate: M - A is positive
  // semi-definite, so every lambda lies in (0, 1].
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0);
  EXPECT_LE(eig.eigenvalues().maxCoeff(), 1 + 1e-12);
  for (const int degree : {1, 2, 3, 4}) {
    const double lower = 0.1;
    ChebyshevSmoother smoother(degree, lower);
    smoother.set_matrix(a);
    const double theta = (1 + lower) / 2, delta = (1 - lower) / 2;
    const double bound = 1 / chebyshev_t(degree, theta / delta);
    for (int j = 0; j < eig.eigenvalues().size(); ++j) {
      const double lambda = eig.eigenvalues()[j];
      const Eigen::VectorXd v = eig.eigenvectors().col(j);
      Eigen::VectorXd x = v;
      smoother.smooth(a, Eigen::VectorXd::Zero(v.size()), x, false);
      const double q = chebyshev_t(degree, (theta - lambda) / delta) * bound;
      // Round-off of `degree` products and solves on a vector of norm |v|.
      EXPECT_LT((x - q * v).norm(), 1e-10 * v.norm()) << "degree " << degree << ", " << lambda;
      if (lambda >= lower) {
        EXPECT_LE(std::abs(q), bound * (1 + 1e-12));
      }
    }
  }
}

TEST(ChebyshevSmoother, SameBitsAtEveryThreadCount) {
  std::mt19937 rng(9);
  const BrcMatrix a = test::random_spd_brc(3000, rng);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * a.block_rows, -1, 1);
  Eigen::VectorXd first;
  set_items_per_thread(1);  // every loop threaded, however short
  for (const int n : {1, 2, 3}) {
    ScopedThreadCount threads(n);
    ChebyshevSmoother smoother(3);
    smoother.set_matrix(a);
    Eigen::VectorXd x;
    smoother.smooth(a, b, x, true);
    smoother.smooth(a, b, x, false);
    if (first.size() == 0) first = x;
    EXPECT_EQ(std::memcmp(x.data(), first.data(), sizeof(double) * x.size()), 0) << n << " threads";
  }
  set_items_per_thread(2048);
}

}  // namespace
}  // namespace corofem
