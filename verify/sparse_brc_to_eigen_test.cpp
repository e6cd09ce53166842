// BRC to Eigen conversions against a dense copy, and CHOLMOD fed the one triangle it reads:
// the multigrid's coarsest level gives it only the upper triangle, taken from A's rows.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "linalg/cholmod_factorization.hpp"
#include "sparse/brc_matrix.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

TEST(BrcToEigen, FullAndUpperCopyEveryValueAndUpdateFollowsNewValues) {
  std::mt19937 rng(7);
  BrcMatrix a = test::random_spd_brc(60, rng);
  BrcToEigen full(a), upper(a, BrcToEigen::Part::SymmetricUpper);
  for (int round = 0; round < 2; ++round) {
    const Eigen::MatrixXd d = test::dense_copy(a);
    // Exact: copies, no arithmetic.
    EXPECT_EQ((Eigen::MatrixXd(full.matrix()) - d).cwiseAbs().maxCoeff(), 0.0);
    const Eigen::MatrixXd upper_of_d = d.triangularView<Eigen::Upper>();
    EXPECT_EQ((Eigen::MatrixXd(upper.matrix()) - upper_of_d).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(upper.matrix().nonZeros(), (full.matrix().nonZeros() + d.rows()) / 2);
    // New values in the same pattern (still symmetric): update() must carry every one.
    for (double& v : a.values) v *= 1.5;
    full.update(a);
    upper.update(a);
  }
}

TEST(BrcToEigen, CholmodOnTheUpperTriangleSolvesLikeADenseCholesky) {
  std::mt19937 rng(11);
  const BrcMatrix a = test::random_spd_brc(80, rng);
  const BrcToEigen upper(a, BrcToEigen::Part::SymmetricUpper);
  CholmodFactorization cholmod;
  cholmod.factorize(upper.matrix());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * a.block_rows, -1, 2);
  const Eigen::MatrixXd d = test::dense_copy(a);
  const Eigen::VectorXd expected = d.llt().solve(b);
  // Both are backward stable: they agree to about cond(A) eps; this A is diagonally dominant
  // (cond < 10), so 1e-12 leaves a margin of 100 over double rounding.
  EXPECT_LE((cholmod.solve(b) - expected).norm(), 1e-12 * expected.norm());
}

}  // namespace
}  // namespace corofem
