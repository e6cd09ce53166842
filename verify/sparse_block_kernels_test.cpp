// The block product's two forms (sparse/block_kernels.hpp) against a dense product, at 1, 2 and
// 3 threads: the AVX2 form's masked loads at the last block and the last vertex, its lane sums,
// and the scalar form that every sweep and every CPU without AVX2 runs.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstring>
#include <limits>
#include <random>

#include "core/threads.hpp"
#include "sparse/block_kernels.hpp"
#include "sparse/brc_matrix.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// Random pattern with the diagonal, the last column in the last row (the masked loads' edge)
/// and rows of 1 to 40 blocks; values in [-1, 1].
BrcMatrix random_brc(int n, std::mt19937& rng) {
  std::uniform_int_distribution<int> column(0, n - 1), count(0, 39);
  std::vector<std::vector<int>> columns(n);
  for (int i = 0; i < n; ++i) {
    std::vector<int>& c = columns[i];
    c.push_back(i);
    for (int k = count(rng); k > 0; --k) c.push_back(column(rng));
    if (i == n - 1) c.push_back(0);  // with the diagonal: the first and the last column
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  BrcMatrix a = make_brc_pattern(n, columns);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& v : a.values) v = u(rng);
  return a;
}

TEST(BlockKernels, BothFormsMatchTheDenseProductAtEveryThreadCount) {
  std::mt19937 rng(7);
  const int n = 3000;  // above the threads' grain, so 2 and 3 threads really split the rows
  const BrcMatrix a = random_brc(n, rng);
  Eigen::VectorXd x = Eigen::VectorXd::Random(3 * n);
  const Eigen::MatrixXd d = test::dense_copy(a);
  const Eigen::VectorXd expected = d * x;
  // Forward error bound of a sum of m products: m u sum |terms| (Higham, Accuracy and Stability,
  // 3.1); a row has at most 41 blocks, so m <= 123 terms: 130 u (|A| |x|)_i bounds both forms.
  const Eigen::VectorXd scale = d.cwiseAbs() * x.cwiseAbs();
  const double u = std::numeric_limits<double>::epsilon() / 2;
  test::in_each_kernel_form([&] {
    Eigen::VectorXd one;
    {
      ScopedThreadCount threads(1);
      a.multiply(x, one);
    }
    for (int i = 0; i < 3 * n; ++i)
      ASSERT_LE(std::abs(one[i] - expected[i]), 130 * u * scale[i]) << "entry " << i;
    // The fused residual is b minus the product, rounded once more: the same bits.
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * n, -1, 1), r_expected = b - one;
    for (const int t : {1, 2, 3}) {
      ScopedThreadCount threads(t);
      Eigen::VectorXd y, r;
      a.multiply(x, y);
      EXPECT_EQ(0, std::memcmp(y.data(), one.data(), sizeof(double) * y.size())) << t << " threads";
      a.residual(b, x, r);
      EXPECT_EQ(0, std::memcmp(r.data(), r_expected.data(), sizeof(double) * r.size()))
          << t << " threads";
    }
  });
}

TEST(BlockKernels, TheSwitchFollowsTheCpuAndTheRecordNamesTheForm) {
  // The AVX2 form may be on only where the CPU reports AVX2 and FMA (asked here independently of
  // the library), and the record's name must follow the switch both ways.
  const bool before = set_vector_block_kernels(true);
#ifdef COROFEM_HAVE_AVX2_KERNELS
  const bool cpu = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  const bool cpu = false;
#endif
  EXPECT_EQ(vector_block_kernels(), cpu);
  EXPECT_STREQ(block_kernels_name(), cpu ? "avx2-fma" : "scalar");
  set_vector_block_kernels(false);
  EXPECT_FALSE(vector_block_kernels());
  EXPECT_STREQ(block_kernels_name(), "scalar");
  set_vector_block_kernels(before);
}

}  // namespace
}  // namespace corofem
