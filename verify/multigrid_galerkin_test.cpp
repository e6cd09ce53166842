// Galerkin products: stream = naive = reuse = Eigen = dense on random small hierarchies and a box
// hierarchy, again after A's values change, and with an entry of A scattered more than 127 times
// (continuation control bytes).
#include <gtest/gtest.h>

#include <random>

#include "galerkin_oracle.hpp"
#include "mesh/box_mesh.hpp"
#include "multigrid/galerkin.hpp"
#include "multigrid/hierarchy.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "fem/assembly_map.hpp"

namespace corofem {
namespace {

/// Random symmetric values on A's (symmetric) pattern: A_ji = A_ij^T, as every system matrix.
void randomize(BrcMatrix& a, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& v : a.values) v = u(rng);
  for (int i = 0; i < a.block_rows; ++i)
    for (int b = a.row_start[i]; b < a.row_start[i + 1]; ++b)
      if (a.col_index[b] < i) {
        a.block(b) = a.block(a.find(a.col_index[b], i)).transpose();
      } else if (a.col_index[b] == i) {
        const Eigen::Matrix3d d = a.block(b);
        a.block(b) = 0.5 * (d + d.transpose());
      }
}

double relative_frobenius(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ref) {
  return (x - ref).norm() / ref.norm();
}

/// All three methods against both oracles for one A and transfer.
void check_all_methods(const BrcMatrix& a, const Transfer& t) {
  BrcMatrix e = galerkin_pattern(a, t);
  const Eigen::SparseMatrix<double> r = restriction_matrix(t);
  const Eigen::MatrixXd dense = reference::dense_galerkin(Eigen::MatrixXd(r), Eigen::MatrixXd(to_eigen(a)));
  const Eigen::MatrixXd eigen = Eigen::MatrixXd(reference::eigen_galerkin(r, to_eigen(a)));
  // Sums of a few dozen products in different orders: round-off ~1e-16 relative.
  EXPECT_LT(relative_frobenius(eigen, dense), 1e-13);
  for (auto symmetry : {GalerkinStream::Symmetry::Symmetric, GalerkinStream::Symmetry::Full}) {
    GalerkinStream stream(a, t, e, symmetry);
    stream.apply(a, e);
    EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "stream";
  }
  galerkin_naive(a, t, e);
  EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "naive";
  GalerkinReuse reuse(t.coarse);
  reuse.apply(a, t, e);
  EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "reuse";
}

TEST(Galerkin, AllMethodsEqualOraclesOnBoxHierarchy) {
  const TetMesh mesh = make_box_mesh({1, 0.8, 0.6}, {5, 4, 3});
  AssemblyMap map;
  BrcMatrix a = make_stiffness_pattern(mesh, map);
  std::mt19937 rng(1);
  randomize(a, rng);
  const CoarseLevel coarse = make_lattice_level(mesh.rest, {}, 0.35);
  ASSERT_GT(coarse.transfer.coarse, 8);
  check_all_methods(a, coarse.transfer);
  randomize(a, rng);  // new values, same stream
  check_all_methods(a, coarse.transfer);
}

TEST(Galerkin, RandomSmallHierarchies) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    std::uniform_int_distribution<int> n(2, 4);
    const TetMesh mesh = make_box_mesh({1, 1, 1}, {n(rng), n(rng), n(rng)});
    AssemblyMap map;
    BrcMatrix a = make_stiffness_pattern(mesh, map);
    randomize(a, rng);
    std::vector<Vec3> jittered = mesh.rest;
    std::uniform_real_distribution<double> u(-0.05, 0.05);
    for (auto& p : jittered) p += Vec3(u(rng), u(rng), u(rng));
    std::vector<char> fixed(mesh.rest.size(), 0);
    fixed[0] = 1;  // a fixed vertex: empty prolongation row
    const CoarseLevel coarse = make_lattice_level(jittered, fixed, std::uniform_real_distribution<double>(0.3, 0.7)(rng));
    check_all_methods(a, coarse.transfer);
  }
}

TEST(Galerkin, ContinuationBytesBeyond127Pairs) {
  // Two fine vertices, each interpolated from 12 coarse vertices: the block A_01 is scattered to
  // 12 x 12 = 144 blocks of E, more than one control byte holds.
  TetMesh mesh = make_box_mesh({1, 1, 1}, {1, 1, 1});
  AssemblyMap map;
  BrcMatrix a = make_stiffness_pattern(mesh, map);
  std::mt19937 rng(3);
  randomize(a, rng);
  Transfer t;
  t.fine = mesh.num_vertices();
  t.coarse = 30;
  t.p_start.push_back(0);
  std::uniform_real_distribution<double> w(0.01, 1);
  for (int l = 0; l < t.fine; ++l) {
    const int parents = l < 2 ? 12 : 2;
    for (int m = 0; m < parents; ++m) {
      t.p_col.push_back(l < 2 ? 2 * m + l : 24 + (l + m) % 6);
      t.p_weight.push_back(w(rng));
    }
    std::sort(t.p_col.begin() + t.p_start.back(), t.p_col.end());
    t.p_start.push_back(static_cast<int>(t.p_col.size()));
  }
  t.transpose_prolongation();
  const BrcMatrix e = galerkin_pattern(a, t);
  const GalerkinStream stream(a, t, e, GalerkinStream::Symmetry::Full);
  int continuation = 0;
  for (std::uint8_t c : stream.control()) continuation += !(c & 0x80);
  EXPECT_GT(continuation, 0);
  check_all_methods(a, t);
}

TEST(Galerkin, HierarchyUpdateMatchesEigenOnEveryLevel) {
  const TetMesh mesh = make_box_mesh({1, 1, 1}, {6, 6, 6});
  AssemblyMap map;
  BrcMatrix a = make_stiffness_pattern(mesh, map);
  std::mt19937 rng(4);
  randomize(a, rng);
  MultigridHierarchy hierarchy(a, mesh.rest, {}, 0.25, 3);
  ASSERT_EQ(hierarchy.num_levels(), 3);
  for (GalerkinMethod m : {GalerkinMethod::Naive, GalerkinMethod::Stream, GalerkinMethod::StreamFull,
                           GalerkinMethod::Reuse}) {
    hierarchy.update(a, m);
    for (int h = 0; h + 1 < hierarchy.num_levels(); ++h) {
      const Eigen::MatrixXd ref = Eigen::MatrixXd(
          reference::eigen_galerkin(restriction_matrix(hierarchy.transfer(h)), to_eigen(hierarchy.matrix(h))));
      EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(hierarchy.matrix(h + 1))), ref), 1e-13);
    }
  }
}

TEST(Transfer, LatticeWeightsInterpolateAffineFieldsExactly) {
  // Barycentric weights reproduce linear functions: sum_i R_il f(x_i) = f(x_l), and sum to 1.
  const TetMesh mesh = make_box_mesh({1, 0.7, 0.4}, {7, 5, 3});
  const CoarseLevel coarse = make_lattice_level(mesh.rest, {}, 0.23);
  const Transfer& t = coarse.transfer;
  auto f = [](const Vec3& x) { return 0.3 + 2 * x.x() - x.y() + 0.5 * x.z(); };
  for (int l = 0; l < t.fine; ++l) {
    double sum = 0, value = 0;
    for (int k = t.p_start[l]; k < t.p_start[l + 1]; ++k) {
      sum += t.p_weight[k];
      value += t.p_weight[k] * f(coarse.points[t.p_col[k]]);
      EXPECT_GE(t.p_weight[k], 0);
    }
    EXPECT_NEAR(sum, 1, 1e-13);
    EXPECT_NEAR(value, f(mesh.rest[l]), 1e-12);
  }
}

}  // namespace
}  // namespace corofem
