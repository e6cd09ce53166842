// Galerkin products: stream = gather = naive = reuse = Eigen = dense on random small hierarchies
// and a box hierarchy, again after A's values change, and with an entry of A scattered more than
// 127 times (continuation control bytes); on nested boxes, the coarse mesh's own stiffness.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/errors.hpp"
#include "element/material.hpp"
#include "fem/assembly_map.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/fe_problem.hpp"
#include "galerkin_oracle.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/rank_part.hpp"
#include "multigrid/galerkin.hpp"
#include "multigrid/galerkin_gather.hpp"
#include "multigrid/galerkin_row_share.hpp"
#include "multigrid/hierarchy.hpp"
#include "multigrid/hierarchy_builder.hpp"
#include "multigrid/lattice_level.hpp"
#include "multigrid/mesh_level.hpp"
#include "solver/petsc_galerkin.hpp"
#include "solver/petsc_solver.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// The mesh's stiffness pattern with random symmetric values.
BrcMatrix random_symmetric(const TetMesh& mesh, std::mt19937& rng) {
  AssemblyMap map;
  BrcMatrix a = make_stiffness_pattern(mesh, map);
  test::randomize_symmetric(a, rng);
  return a;
}

double relative_frobenius(const Eigen::MatrixXd& x, const Eigen::MatrixXd& ref) {
  return (x - ref).norm() / ref.norm();
}

/// All three methods against both oracles for one A and transfer.
void check_all_methods(const BrcMatrix& a, const Transfer& t) {
  BrcMatrix e = galerkin_pattern(a, t);
  const Eigen::SparseMatrix<double> r = restriction_matrix(t);
  const Eigen::MatrixXd dense =
      reference::dense_galerkin(Eigen::MatrixXd(r), Eigen::MatrixXd(to_eigen(a)));
  const Eigen::MatrixXd eigen = Eigen::MatrixXd(reference::eigen_galerkin(r, to_eigen(a)));
  // Sums of a few dozen products in different orders: round-off ~1e-16 relative.
  EXPECT_LT(relative_frobenius(eigen, dense), 1e-13);
  // The stream in each form of its scatter (sparse/block_kernels.hpp).
  test::in_each_kernel_form([&] {
    for (auto symmetry : {GalerkinStream::Symmetry::Symmetric, GalerkinStream::Symmetry::Full}) {
      GalerkinStream stream(a, t, e, symmetry);
      stream.apply(a, e);
      EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "stream";
    }
    GalerkinReuse reuse(t.coarse);
    reuse.apply(a, t, e);
    EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "reuse";
    // The gather stream adds the symmetric stream's pairs in the same order with the same
    // operations: the same bits, for any number of parts (threads' row ranges). E is filled with
    // garbage first: the gather writes every block.
    GalerkinStream stream(a, t, e, GalerkinStream::Symmetry::Symmetric);
    stream.apply(a, e);
    const std::vector<double> streamed = e.values;
    for (int parts : {1, 2, 3}) {
      std::fill(e.values.begin(), e.values.end(), std::numeric_limits<double>::quiet_NaN());
      GalerkinGather gather(a, t, e, parts);
      EXPECT_EQ(gather.num_pairs(), stream.num_pairs());
      gather.apply(a, e);
      EXPECT_TRUE(e.values == streamed) << "gather, " << parts << " parts";
      EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "gather";
    }
  });
  galerkin_naive(a, t, e);
  EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), dense), 1e-13) << "naive";
}

TEST(Galerkin, AllMethodsEqualOraclesOnBoxHierarchy) {
  const TetMesh mesh = make_box_mesh({1, 0.8, 0.6}, {5, 4, 3});
  std::mt19937 rng(1);
  BrcMatrix a = random_symmetric(mesh, rng);
  const CoarseLevel coarse = make_lattice_level(mesh.rest, {}, 0.35);
  ASSERT_GT(coarse.transfer.coarse, 8);
  check_all_methods(a, coarse.transfer);
  test::randomize_symmetric(a, rng);  // new values, same stream
  check_all_methods(a, coarse.transfer);
}

TEST(Galerkin, RandomSmallHierarchies) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    std::uniform_int_distribution<int> n(2, 4);
    const TetMesh mesh = make_box_mesh({1, 1, 1}, {n(rng), n(rng), n(rng)});
    BrcMatrix a = random_symmetric(mesh, rng);
    std::vector<Vec3> jittered = mesh.rest;
    std::uniform_real_distribution<double> u(-0.05, 0.05);
    for (auto& p : jittered) p += Vec3(u(rng), u(rng), u(rng));
    std::vector<char> fixed(mesh.rest.size(), 0);
    fixed[0] = 1;  // a fixed vertex: empty prolongation row
    const CoarseLevel coarse =
        make_lattice_level(jittered, fixed, std::uniform_real_distribution<double>(0.3, 0.7)(rng));
    check_all_methods(a, coarse.transfer);
  }
}

TEST(Galerkin, ContinuationBytesBeyond127Pairs) {
  // Two fine vertices, each interpolated from 12 coarse vertices: the block A_01 is scattered to
  // 12 x 12 = 144 blocks of E, more than one control byte holds.
  TetMesh mesh = make_box_mesh({1, 1, 1}, {1, 1, 1});
  std::mt19937 rng(3);
  BrcMatrix a = random_symmetric(mesh, rng);
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
  const GalerkinStream stream(a, t, e, GalerkinStream::Symmetry::Full,
                              1);  // one stream: the paper's
  int continuation = 0;
  for (std::uint8_t c : stream.control()) continuation += !(c & 0x80);
  EXPECT_GT(continuation, 0);
  check_all_methods(a, t);
}

/// Every method on every level of the hierarchy against the dense and Eigen oracles.
void check_hierarchy(const BrcMatrix& a, std::vector<Transfer> transfers, int levels) {
  MultigridHierarchy hierarchy(a, std::move(transfers));
  ASSERT_EQ(hierarchy.num_levels(), levels);
  for (GalerkinMethod m :
       {GalerkinMethod::Naive, GalerkinMethod::Stream, GalerkinMethod::StreamFull,
        GalerkinMethod::Reuse, GalerkinMethod::Gather}) {
    hierarchy.update(a, m);
    for (int h = 0; h + 1 < hierarchy.num_levels(); ++h) {
      const Eigen::SparseMatrix<double> r = restriction_matrix(hierarchy.transfer(h));
      const Eigen::MatrixXd fine = Eigen::MatrixXd(to_eigen(hierarchy.matrix(h)));
      const Eigen::MatrixXd dense = reference::dense_galerkin(Eigen::MatrixXd(r), fine);
      const Eigen::MatrixXd eigen =
          Eigen::MatrixXd(reference::eigen_galerkin(r, to_eigen(hierarchy.matrix(h))));
      const Eigen::MatrixXd got = Eigen::MatrixXd(to_eigen(hierarchy.matrix(h + 1)));
      // Sums of a few hundred products in different orders: round-off ~1e-15 relative.
      EXPECT_LT(relative_frobenius(got, dense), 1e-13) << "level " << h + 1;
      EXPECT_LT(relative_frobenius(got, eigen), 1e-13) << "level " << h + 1;
    }
  }
}

/// The transfers of a lattice hierarchy over the mesh, level-1 cells of the given size.
std::vector<Transfer> lattice_transfers(const TetMesh& mesh, double cell) {
  HierarchyParams params;
  params.kind = HierarchyKind::Lattice;
  params.first_cell_factor = cell / mean_edge_length(mesh);
  return build_hierarchy(mesh, {}, params).transfers;
}

TEST(Galerkin, LatticeHierarchyUpdateMatchesOraclesOnEveryLevel) {
  const TetMesh mesh = make_box_mesh({1, 1, 1}, {6, 6, 6});
  std::mt19937 rng(4);
  BrcMatrix a = random_symmetric(mesh, rng);
  check_hierarchy(a, lattice_transfers(mesh, 0.25), 3);
}

TEST(Galerkin, StreamsBuiltOnFirstUseGiveThePreparedBits) {
  // A method's streams are built on first use, from the patterns only: built in the set-up
  // (prepare) or lazily after other methods have filled the levels, every level gets the same
  // bits; the methods that precompute nothing report no stream bytes.
  const TetMesh mesh = make_box_mesh({1, 1, 1}, {5, 5, 5});
  std::mt19937 rng(8);
  BrcMatrix a = random_symmetric(mesh, rng);
  const std::vector<Transfer> transfers = lattice_transfers(mesh, 0.3);
  for (const GalerkinMethod m :
       {GalerkinMethod::Stream, GalerkinMethod::StreamFull, GalerkinMethod::Gather}) {
    MultigridHierarchy prepared(a, transfers), lazy(a, transfers);
    prepared.prepare(m);
    prepared.update(a, m);
    lazy.update(a, GalerkinMethod::Naive);
    lazy.update(a, m);
    for (int h = 0; h < prepared.num_levels(); ++h)
      EXPECT_TRUE(lazy.matrix(h).values == prepared.matrix(h).values) << "level " << h;
    std::size_t bytes = 0;
    for (int h = 0; h + 1 < prepared.num_levels(); ++h)
      bytes += m == GalerkinMethod::Gather       ? prepared.gather(h).bytes()
               : m == GalerkinMethod::StreamFull ? prepared.full_stream(h).bytes()
                                                 : prepared.stream(h).bytes();
    EXPECT_GT(bytes, 0u);
    EXPECT_EQ(prepared.stream_bytes(m), bytes);
  }
  MultigridHierarchy h(a, transfers);
  EXPECT_EQ(h.stream_bytes(GalerkinMethod::Naive), 0u);
  EXPECT_EQ(h.stream_bytes(GalerkinMethod::Reuse), 0u);
}

TEST(Galerkin, TakenFineValuesGiveTheCopiedUpdateBits) {
  // take_update swaps the fine values in instead of copying them: every level the same bits as
  // update's, the caller left with a matrix of the same pattern, and another pattern refused.
  const TetMesh mesh = make_box_mesh({1, 1, 1}, {5, 5, 5});
  std::mt19937 rng(6);
  BrcMatrix a = random_symmetric(mesh, rng);
  const std::vector<Transfer> transfers = lattice_transfers(mesh, 0.3);
  MultigridHierarchy copied(a, transfers), taken(a, transfers);
  for (int round = 0; round < 2; ++round) {
    test::randomize_symmetric(a, rng);
    copied.update(a);
    BrcMatrix handed = a;
    taken.take_update(handed);
    EXPECT_EQ(handed.values.size(), a.values.size());
    EXPECT_EQ(handed.col_index, a.col_index);
    ASSERT_EQ(taken.num_levels(), copied.num_levels());
    for (int h = 0; h < copied.num_levels(); ++h)
      EXPECT_TRUE(taken.matrix(h).values == copied.matrix(h).values)
          << "level " << h << ", round " << round;
  }
  BrcMatrix other = random_symmetric(make_box_mesh({1, 1, 1}, {2, 2, 2}), rng);
  EXPECT_THROW(taken.take_update(other), std::logic_error);
}

TEST(Galerkin, MeshHierarchyUpdateMatchesOraclesOnEveryLevel) {
  // Three gmsh meshes of one cube at sizes h, 2h, 4h: non-nested levels, as in the paper; the
  // fine one with some vertices fixed (no weights) and a jittered copy of the middle level,
  // so that fine vertices fall outside it and are extrapolated.
  test::TempDir dir;
  for (int n : {2, 4, 8})
    test::write_text(dir / ("cube" + std::to_string(n) + ".stl"), test::cube_stl(n));
  const TetMesh fine = tetrahedralize_surface(dir / "cube8.stl", 0.15);
  std::vector<TetMesh> coarse = {tetrahedralize_surface(dir / "cube4.stl", 0.3),
                                 tetrahedralize_surface(dir / "cube2.stl", 0.6)};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (Vec3& x : coarse[0].rest) x += Vec3(jitter(rng), jitter(rng), jitter(rng));
  BrcMatrix a = random_symmetric(fine, rng);
  std::vector<char> fixed(fine.rest.size(), 0);
  for (int v = 0; v < fine.num_vertices(); ++v) fixed[v] = fine.rest[v].x() < 1e-9;
  HierarchyParams params;
  params.kind = HierarchyKind::Meshes;
  const BuiltHierarchy built = build_hierarchy(fine, fixed, params, coarse);
  EXPECT_GT(built.levels[0].fit.outside, 0) << "the jitter should leave points outside";
  check_hierarchy(a, built.transfers, 3);
  // PETSc's MatPtAP (issue 14's rival product) on the same matrices: symbolic + numeric, then
  // numeric reuse with new values, each level against our stream's (both exact sums of the
  // same products: rounding only).
  if (!have_petsc()) {
    EXPECT_THROW(PetscPtapHierarchy(a, built.transfers), InputError);
    return;
  }
  MultigridHierarchy ours(a, built.transfers);
  PetscPtapHierarchy theirs(a, built.transfers);
  for (int round = 0; round < 2; ++round) {
    if (round == 1)
      for (double& v : a.values) v *= 1.5;  // numeric-only update of a symmetric A stays symmetric
    ours.update(a, GalerkinMethod::Stream);
    theirs.update(a);
    ASSERT_EQ(theirs.num_levels(), 3);
    for (int h = 1; h < 3; ++h) {
      const Eigen::MatrixXd e = Eigen::MatrixXd(to_eigen(ours.matrix(h)));
      const Eigen::MatrixXd p = Eigen::MatrixXd(theirs.level(h));
      ASSERT_EQ(p.rows(), e.rows());
      EXPECT_LT((p - e).norm(), 1e-12 * e.norm()) << "level " << h << ", round " << round;
    }
  }
}

TEST(Galerkin, NestedKuhnBoxesGiveTheCoarseMeshesOwnStiffness) {
  // The variational property of a nested hierarchy: where every coarse tet is a union of fine
  // ones (Kuhn cells split into 8 Kuhn cells each), the coarse P1 space lies in the fine one, the
  // transfer's barycentric weights reproduce each coarse hat function exactly, and R K_h R^T is
  // the coarse mesh's own stiffness K_H, assembled by the element code on the coarse tets. An
  // oracle independent of the transfer's and the product's code: a point located in a wrong tet,
  // a wrong weight, a product that drops or doubles a pair, each breaks it.
  const Vec3 size(1, 0.8, 0.6);
  const TetMesh fine = make_box_mesh(size, {8, 6, 4}), coarse = make_box_mesh(size, {4, 3, 2});
  const auto stiffness = [](const TetMesh& mesh) {
    FeProblem p = make_fe_problem(mesh, materials_per_element(mesh, Material{1e6, 0.3, 1000}, {}));
    const std::vector<Mat3> identity(mesh.tets.size(), Mat3::Identity());
    Eigen::VectorXd force;
    assemble_corotated(p.elements, p.mesh, p.assembly, identity,
                       Eigen::VectorXd::Zero(p.num_dofs()), p.stiffness, force);
    return p.stiffness;
  };
  MeshLevelFit fit;
  const CoarseLevel level = make_mesh_level(fine.rest, std::vector<char>(fine.rest.size(), 0),
                                            coarse, "coarse box", &fit);
  EXPECT_EQ(fit.outside, 0);
  EXPECT_EQ(fit.dropped_vertices, 0);  // so the coarse numbering is the mesh's
  ASSERT_EQ(level.transfer.coarse, coarse.num_vertices());
  const BrcMatrix a = stiffness(fine);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(to_eigen(stiffness(coarse)));
  BrcMatrix e = galerkin_pattern(a, level.transfer);
  GalerkinStream(a, level.transfer, e, GalerkinStream::Symmetry::Symmetric).apply(a, e);
  // Weights 1, 1/2 (edge midpoints) and sums of a few dozen products: round-off ~1e-16.
  EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), expected), 1e-13) << "stream";
  galerkin_naive(a, level.transfer, e);
  EXPECT_LT(relative_frobenius(Eigen::MatrixXd(to_eigen(e)), expected), 1e-13) << "naive";
}

/// The shares of a partition's parts sum to R A R^T, whether each part holds its rows in its own
/// numbering (a distributed mesh's part: owned vertices, then the halo, with P's rows of both)
/// or the whole matrix and transfer with its rows a range of them (replicated).
TEST(GalerkinRowShare, PartsSharesSumToTheWholeProduct) {
  const TetMesh mesh = make_box_mesh({1, 0.8, 0.6}, {6, 5, 4});
  std::mt19937 rng(7);
  const BrcMatrix a = random_symmetric(mesh, rng);
  const CoarseLevel coarse = make_lattice_level(mesh.rest, {}, 0.3);
  const Transfer& t = coarse.transfer;
  const Eigen::MatrixXd whole = reference::dense_galerkin(Eigen::MatrixXd(restriction_matrix(t)),
                                                          Eigen::MatrixXd(to_eigen(a)));
  const int nv = mesh.num_vertices();
  const std::vector<int> first = {0, nv / 4, nv / 2 + 3, nv};  // uneven ranges
  Eigen::MatrixXd distributed = Eigen::MatrixXd::Zero(whole.rows(), whole.cols());
  Eigen::MatrixXd replicated = distributed;
  for (std::size_t r = 0; r + 1 < first.size(); ++r) {
    const RankPart part = rank_part_of_range(mesh, first[r], first[r + 1]);
    ASSERT_GT(part.halo_vertices, 0);
    AssemblyMap map;
    BrcMatrix local = make_stiffness_pattern(part.mesh, map);
    for (int i = 0; i < local.block_rows; ++i)
      for (int k = local.row_start[i]; k < local.row_start[i + 1]; ++k) {
        const int b = a.find(part.global_vertex[i], part.global_vertex[local.col_index[k]]);
        ASSERT_GE(b, 0);
        std::copy_n(a.values.begin() + 9 * b, 9, local.values.begin() + 9 * k);
      }
    GalerkinRowShare share(local, rows_of(t, part.global_vertex), 0, part.owned_vertices);
    share.apply(local);
    distributed += Eigen::MatrixXd(to_eigen(share.share()));
    GalerkinRowShare range(a, t, first[r], first[r + 1]);
    range.apply(a);
    replicated += Eigen::MatrixXd(to_eigen(range.share()));
  }
  // Sums of a few dozen products in other orders: round-off ~1e-16 relative.
  EXPECT_LT(relative_frobenius(distributed, whole), 1e-13);
  EXPECT_LT(relative_frobenius(replicated, whole), 1e-13);
  // A part's share is not the whole product (the check can fail).
  GalerkinRowShare half(a, t, 0, nv / 2);
  half.apply(a);
  EXPECT_GT(relative_frobenius(Eigen::MatrixXd(to_eigen(half.share())), whole), 0.1);
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
