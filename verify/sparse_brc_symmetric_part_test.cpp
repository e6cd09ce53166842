// The symmetric part (A + A^T) / 2 on A's own pattern, against the dense one: what Newton's
// tangent solves precondition (a Cholesky factor, or the multigrid).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>

#include "sparse/brc_matrix.hpp"
#include "sparse/brc_symmetric_part.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

TEST(BrcSymmetricPart, EqualsTheDenseSymmetricPartOfEveryNewMatrix) {
  std::mt19937 rng(5);
  BrcMatrix a = test::random_spd_brc(50, rng);
  BrcSymmetricPart part(a);
  ASSERT_TRUE(part.pattern_symmetric());
  std::uniform_real_distribution<double> skew(-1.0, 1.0);
  for (int round = 0; round < 2; ++round) {
    for (double& v : a.values) v += skew(rng);  // no longer symmetric, same pattern
    const Eigen::MatrixXd d = test::dense_copy(a);
    ASSERT_GT((d - d.transpose()).norm(), 1e-3 * d.norm());
    // Exact: each entry is 0.5 * (x + y) in both, and IEEE addition commutes.
    const Eigen::MatrixXd expected = 0.5 * (d + d.transpose());
    EXPECT_EQ((test::dense_copy(part.of(a)) - expected).cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(BrcSymmetricPart, APatternWithoutTransposedPartnersIsRefused) {
  // Block (0, 1) without (1, 0): the symmetric part does not fit the pattern.
  const BrcMatrix a = make_brc_pattern(2, {{0, 1}, {1}});
  BrcSymmetricPart part(a);
  EXPECT_FALSE(part.pattern_symmetric());
  EXPECT_THROW(part.of(a), std::logic_error);
}

}  // namespace
}  // namespace corofem
