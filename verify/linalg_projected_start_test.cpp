// The projected start (linalg/projected_start.hpp) against its definition, a dense oracle: of all
// x in the span of the kept solutions, the one with the least A-norm error, x0 = V (V^T A V)^-1
// V^T b, solved here with a dense LDLT on a well-conditioned V; and against the linear
// extrapolation it replaces, which lies in that span.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "linalg/projected_start.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

double energy_norm(const Eigen::MatrixXd& a, const Eigen::VectorXd& e) {
  return std::sqrt(e.dot(a * e));
}

class ProjectedStartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    a_ = test::random_spd_brc(40, rng_);
    dense_ = test::dense_copy(a_);
    b_ = Eigen::VectorXd::Random(dense_.rows());
    solution_ = dense_.ldlt().solve(b_);
  }
  std::mt19937 rng_{7};
  BrcMatrix a_;
  Eigen::MatrixXd dense_;
  Eigen::VectorXd b_, solution_;
};

TEST_F(ProjectedStartTest, EqualsTheDenseGalerkinProjectionOnTheLastSolutions) {
  ProjectedStart projection(3);
  std::vector<Eigen::VectorXd> kept;
  Eigen::VectorXd start;
  for (int step = 0; step < 5; ++step) {  // five solutions seen, the last three kept
    const Eigen::VectorXd latest = Eigen::VectorXd::Random(dense_.rows());
    kept.insert(kept.begin(), latest);
    if (kept.size() > 3) kept.pop_back();
    ASSERT_TRUE(projection.compute(a_, b_, latest, start));
    Eigen::MatrixXd v(dense_.rows(), static_cast<int>(kept.size()));
    for (int i = 0; i < v.cols(); ++i) v.col(i) = kept[i];
    const Eigen::VectorXd oracle =
        v * (v.transpose() * dense_ * v).ldlt().solve(v.transpose() * b_);
    // random columns: V^T A V has a condition number near 1e2, so both agree to ~1e-13
    EXPECT_LT((start - oracle).norm(), 1e-10 * oracle.norm()) << "step " << step;
  }
}

TEST_F(ProjectedStartTest, IsNoWorseThanTheExtrapolationAndExactWhenTheSolutionIsInTheSpan) {
  // Successive solutions nearly parallel, as a simulation's velocities: the Gram matrix is then
  // nearly singular, the case the scaled pseudo-inverse is there for.
  const Eigen::VectorXd drift = Eigen::VectorXd::Random(dense_.rows());
  ProjectedStart projection(4);
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(dense_.rows()), start;
  for (int step = 1; step <= 6; ++step) {
    const Eigen::VectorXd latest =
        solution_ + std::pow(0.5, step) * drift + 1e-6 * Eigen::VectorXd::Random(dense_.rows());
    ASSERT_TRUE(projection.compute(a_, b_, latest, start));
    const Eigen::VectorXd extrapolated = 2 * latest - previous;
    EXPECT_LE(energy_norm(dense_, start - solution_),
              energy_norm(dense_, extrapolated - solution_) * (1 + 1e-8))
        << "step " << step;
    previous = latest;
  }
  // The solution itself a combination of the kept vectors: the projection finds it, to the
  // round-off of a 2 x 2 Gram matrix of two random vectors (well conditioned).
  ProjectedStart exact(3);
  const Eigen::VectorXd u = Eigen::VectorXd::Random(dense_.rows());
  ASSERT_TRUE(exact.compute(a_, b_, solution_ - u, start));
  ASSERT_TRUE(exact.compute(a_, b_, u, start));
  EXPECT_LT((start - solution_).norm(), 1e-10 * solution_.norm());
}

TEST_F(ProjectedStartTest, ZeroSolutionsLeaveTheStartAlone) {
  ProjectedStart projection(2);
  Eigen::VectorXd start = Eigen::VectorXd::Constant(dense_.rows(), 3.0);
  EXPECT_FALSE(projection.compute(a_, b_, Eigen::VectorXd::Zero(dense_.rows()), start));
  EXPECT_EQ(start, Eigen::VectorXd::Constant(dense_.rows(), 3.0));
  EXPECT_THROW(ProjectedStart(1), std::invalid_argument);
}

}  // namespace
}  // namespace corofem
