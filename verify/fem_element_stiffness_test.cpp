// Element stiffness: symmetry, semidefiniteness, the 6-dimensional rigid null space, and blocks
// computed by hand for the unit right tet.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "element/element_stiffness.hpp"

namespace corofem {
namespace {

const Material kSteelish{2e11, 0.3, 7800};

Mat12 unit_tet_stiffness(const Material& m) {
  return element_stiffness({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, m);
}

TEST(ElementStiffness, MatchesHandComputedUnitTet) {
  // grad N1 = e1, grad N2 = e2, V = 1/6: K_11 = V diag(l + 2m, m, m), K_12 = V (l e1 e2^T + m e2
  // e1^T).
  const Material m{1000, 0.25, 1};
  const double l = m.lame_lambda(), mu = m.lame_mu(), v = 1.0 / 6;
  ASSERT_NEAR(l, 400, 1e-12);
  ASSERT_NEAR(mu, 400, 1e-12);
  const Mat12 k = unit_tet_stiffness(m);
  Mat3 k11 = Mat3::Zero();
  k11.diagonal() << v * (l + 2 * mu), v * mu, v * mu;
  Mat3 k12 = Mat3::Zero();
  k12(0, 1) = v * l;
  k12(1, 0) = v * mu;
  EXPECT_LT((k.block<3, 3>(3, 3) - k11).norm(), 1e-12 * k11.norm());
  EXPECT_LT((k.block<3, 3>(3, 6) - k12).norm(), 1e-12 * k11.norm());
  // grad N0 = (-1,-1,-1): K_00 = V (l + m) 11^T + V m |g|^2 I = V((l+m) 11^T + 3m I).
  const Mat3 k00 = v * ((l + mu) * Mat3::Ones() + 3 * mu * Mat3::Identity());
  EXPECT_LT((k.block<3, 3>(0, 0) - k00).norm(), 1e-12 * k00.norm());
}

class RandomTets : public ::testing::TestWithParam<int> {};

TEST_P(RandomTets, SymmetricPsdWithRigidNullSpace) {
  std::mt19937 rng(GetParam());
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 x[4];
  do {
    for (auto& p : x) p = Vec3(u(rng), u(rng), u(rng));
  } while (signed_volume(x[0], x[1], x[2], x[3]) < 0.01);
  const Mat12 k = element_stiffness(x[0], x[1], x[2], x[3], kSteelish);
  const double scale = k.norm();
  // Symmetry: assembled from exact transposes, so equal to round-off of a few flops.
  EXPECT_LT((k - k.transpose()).norm(), 1e-14 * scale);
  Eigen::SelfAdjointEigenSolver<Mat12> eig(k);
  const auto& lambda = eig.eigenvalues();
  // Round-off in eigenvalues is ~1e-15 |K|; zero modes below 1e-10 |K|, the rest well above.
  int zeros = 0;
  for (int i = 0; i < 12; ++i) {
    EXPECT_GT(lambda[i], -1e-10 * scale);
    zeros += std::abs(lambda[i]) < 1e-10 * scale;
  }
  EXPECT_EQ(zeros, 6);
  // Rigid modes: translations and infinitesimal rotations w x x_a.
  for (int d = 0; d < 6; ++d) {
    Vec12 mode;
    for (int a = 0; a < 4; ++a) {
      Vec3 e = Vec3::Unit(d % 3);
      mode.segment<3>(3 * a) = d < 3 ? e : Vec3(e.cross(x[a]));
    }
    EXPECT_LT((k * mode).norm(), 1e-12 * scale * mode.norm()) << "mode " << d;
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomTets, ::testing::Range(1, 21));

}  // namespace
}  // namespace corofem
