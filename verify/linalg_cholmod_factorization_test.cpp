// CHOLMOD's two factorizations (linalg/factorization_kind.hpp) against a dense Cholesky, failing
// alike on a matrix that is not positive definite, and the simplicial one, which takes no BLAS
// turn, giving the same bits in threads side by side as alone.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "linalg/cholmod_factorization.hpp"
#include "sparse/brc_matrix.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

class BothFactorizations : public ::testing::TestWithParam<Factorization> {};

TEST_P(BothFactorizations, SolveLikeADenseCholesky) {
  std::mt19937 rng(23);
  const BrcMatrix a = test::random_spd_brc(120, rng);
  const BrcToEigen upper(a, BrcToEigen::Part::SymmetricUpper);
  CholmodFactorization cholmod(GetParam());
  cholmod.factorize(upper.matrix());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * a.block_rows, -2, 1);
  const Eigen::VectorXd expected = test::dense_copy(a).llt().solve(b);
  // Both backward stable; this A is diagonally dominant (cond < 10): 1e-12 leaves 100x over eps.
  EXPECT_LE((cholmod.solve(b) - expected).norm(), 1e-12 * expected.norm());
  EXPECT_GT(cholmod.factor_nonzeros(), 0);
}

TEST_P(BothFactorizations, RefuseAMatrixThatIsNotPositiveDefinite) {
  std::mt19937 rng(5);
  BrcMatrix a = test::random_spd_brc(40, rng);
  const BrcToEigen upper(a, BrcToEigen::Part::SymmetricUpper);
  CholmodFactorization cholmod(GetParam());
  cholmod.factorize(upper.matrix());  // positive definite: factors
  for (double& v : a.values) v = -v;  // negative definite: the first pivot fails
  const BrcToEigen negated(a, BrcToEigen::Part::SymmetricUpper);
  EXPECT_THROW(cholmod.factorize(negated.matrix()), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Kinds, BothFactorizations,
                         ::testing::Values(Factorization::Supernodal, Factorization::Simplicial),
                         [](const auto& info) {
                           return std::string(kFactorizations.name(info.param));
                         });

/// Solves with each of `matrices` `rounds` times, each solution appended.
std::vector<Eigen::VectorXd> factor_and_solve(
    const std::vector<Eigen::SparseMatrix<double>>& matrices, int rounds) {
  std::vector<Eigen::VectorXd> out;
  for (int round = 0; round < rounds; ++round)
    for (const auto& m : matrices) {
      CholmodFactorization cholmod(Factorization::Simplicial);
      cholmod.factorize(m);
      out.push_back(cholmod.solve(Eigen::VectorXd::LinSpaced(m.rows(), 1, 3)));
    }
  return out;
}

TEST(SimplicialFactorization, ThreadsSideBySideGiveTheBitsOfOneThread) {
  // Supernodal factorizations side by side corrupted each other through Debian's serial OpenBLAS
  // before they took turns (linalg/blas_turn.hpp); simplicial ones call no BLAS and take none.
  std::mt19937 rng(17);
  std::vector<Eigen::SparseMatrix<double>> first, second;
  for (int k = 0; k < 3; ++k) {
    first.push_back(
        BrcToEigen(test::random_spd_brc(120, rng), BrcToEigen::Part::SymmetricUpper).matrix());
    second.push_back(
        BrcToEigen(test::random_spd_brc(120, rng), BrcToEigen::Part::SymmetricUpper).matrix());
  }
  const int rounds = 10;
  const std::vector<Eigen::VectorXd> alone_first = factor_and_solve(first, rounds);
  const std::vector<Eigen::VectorXd> alone_second = factor_and_solve(second, rounds);
  std::vector<Eigen::VectorXd> beside_first, beside_second;
  std::thread other([&] { beside_second = factor_and_solve(second, rounds); });
  beside_first = factor_and_solve(first, rounds);
  other.join();
  ASSERT_EQ(beside_first.size(), alone_first.size());
  for (std::size_t i = 0; i < alone_first.size(); ++i) {
    EXPECT_EQ(beside_first[i], alone_first[i]) << "solve " << i;
    EXPECT_EQ(beside_second[i], alone_second[i]) << "solve " << i;
  }
}

}  // namespace
}  // namespace corofem
