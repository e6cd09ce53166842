// Threads (issue 12): every threaded kernel at 1, 2 and 3 threads against its one-thread bits and
// against its oracle (Eigen products, the dense Galerkin product, CHOLMOD), and whole dynamic
// runs bit-identical at every thread count and run to run. Every kernel writes each output from
// one thread and sums in a fixed order, so "equal" here means equal bits, not a tolerance.
#include "core/threads.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cstring>
#include <map>
#include <random>

#include "core/errors.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/fe_problem.hpp"
#include "galerkin_oracle.hpp"
#include "linalg/gauss_seidel.hpp"
#include "multigrid/galerkin.hpp"
#include "multigrid/hierarchy.hpp"
#include "multigrid/mesh_level.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene_simulation.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

const int kThreadCounts[] = {1, 2, 3};

/// The gates' meshes are small: every kernel threads them anyway (production skips threads for
/// loops of fewer than 2048 items per thread).
class ThreadsTest : public ::testing::Test {
 protected:
  void SetUp() override { set_items_per_thread(1); }
  void TearDown() override { set_items_per_thread(2048); }
};

bool same_bits(const double* a, const double* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}
bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && same_bits(a.data(), b.data(), a.size());
}
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && same_bits(a.data(), b.data(), a.size());
}

/// A quadruped (thin legs: rows of very different lengths) with its rest positions disturbed.
SceneSimulation quadruped(double size, const std::string& smoother = "multicolour") {
  const nlohmann::json scene = {
      {"mesh", {{"shape", "quadruped"}, {"size", size}, {"reorder", true}}},
      {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
      {"fixed", {{{"box", {{0, -0.3, -0.01}, {0.3, 0.3, 0.05}}}}}},
      {"gravity", {0, 0, -9.81}},
      {"analysis",
       {{"type", "dynamic"},
        {"rotation", "energy-newton"},
        {"solver", "mgpcg"},
        {"smoother", smoother},
        {"dt", 0.01},
        {"steps", 6},
        {"tolerance", 1e-6}}}};
  return SceneSimulation(parse_scene(scene, ".", "threads"));
}

/// `pattern` with random symmetric values (test::randomize_symmetric).
BrcMatrix random_symmetric(BrcMatrix pattern, unsigned seed) {
  std::mt19937 rng(seed);
  test::randomize_symmetric(pattern, rng);
  return pattern;
}

std::vector<Vec3> deformed(const TetMesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.02, 0.02);
  std::vector<Vec3> p = mesh.rest;
  for (Vec3& x : p)
    x = Eigen::AngleAxisd(0.6, Vec3(0.3, 1, 0.2).normalized()) * x + Vec3(d(rng), d(rng), d(rng));
  return p;
}

TEST_F(ThreadsTest, CountIsValidatedAndParsed) {
  EXPECT_THROW(set_thread_count(0), InputError);
  EXPECT_THROW(parse_thread_count("two"), InputError);
  EXPECT_THROW(parse_thread_count("2x"), InputError);
  EXPECT_EQ(parse_thread_count("3"), 3);
  EXPECT_EQ(parse_thread_count("all"), available_cores());
  const std::vector<long long> prefix = {0, 5, 5, 6, 20, 21};
  const std::vector<int> r = balanced_ranges(prefix, 2);
  EXPECT_EQ(r, (std::vector<int>{0, 3, 5}));  // weight 6 | 15: the boundary nearest 21/2
  // Small loops stay on one thread; large ones use every thread, never more than they fill.
  set_items_per_thread(2048);
  const ScopedThreadCount three(3);
  EXPECT_EQ(threads_for(100), 1);
  EXPECT_EQ(threads_for(5000), 2);
  EXPECT_EQ(threads_for(1 << 20), 3);
  set_items_per_thread(1);
}

TEST(Threads, TheAssemblyHasAPartPerThreadItsSizeUses) {
  // A part more than the threads the assembly will use (threads_for its elements, 2048 a thread)
  // visits its boundary elements twice on one thread for nothing: at two threads a mesh under
  // 4096 tets is one part, a larger one two.
  const ScopedThreadCount two(2);
  for (const int cells : {8, 14}) {
    const nlohmann::json scene = {
        {"mesh", {{"box", {1, 1, 1}}, {"cells", {cells, cells, cells}}}},
        {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
        {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 1, 1}}}}}},
        {"analysis", {{"type", "dynamic"}, {"solver", "cholmod"}, {"steps", 1}}}};
    SceneSimulation sim(parse_scene(scene, ".", "box"));
    const int tets = sim.problem().mesh.num_tets();
    SCOPED_TRACE(tets);
    EXPECT_EQ(sim.problem().assembly.rows.parts(), tets < 2 * 2048 ? 1 : 2);
  }
}

TEST_F(ThreadsTest, RotationsAssemblyAndForcesAreTheOneThreadBits) {
  std::map<std::string, std::vector<Mat3>> rotations_one;  // every method's one-thread rotations
  Eigen::VectorXd fused_one, force_one;
  std::vector<double> k_one;
  for (const int n : kThreadCounts) {
    ScopedThreadCount threads(n);
    SceneSimulation sim = quadruped(0.12);  // its row partition has n parts
    FeProblem& p = sim.problem();
    ASSERT_EQ(p.assembly.rows.parts(), n);
    const std::vector<Vec3> x = deformed(p.mesh, 3);
    Eigen::VectorXd u(p.num_dofs());
    for (int v = 0; v < p.mesh.num_vertices(); ++v) u.segment<3>(3 * v) = x[v] - p.mesh.rest[v];
    for (const std::string& method : rotation_method_names()) {
      std::vector<Mat3> r(p.mesh.tets.size(), Mat3::Identity());
      make_rotation_extractor(rotation_method_named(method), p.mesh)->extract(x, r);
      if (n == 1) rotations_one[method] = r;
      const std::vector<Mat3>& one = rotations_one[method];
      for (std::size_t e = 0; e < r.size(); ++e)
        ASSERT_TRUE(same_bits(r[e].data(), one[e].data(), 9))
            << method << " element " << e << " at " << n;
    }
    std::vector<Mat3> r(p.mesh.tets.size(), Mat3::Identity());
    make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh)->extract(x, r);
    Eigen::VectorXd fused;  // the assembly's elastic force
    assemble_corotated(p.elements, p.mesh, p.assembly, r, u, p.stiffness, fused);
    const Eigen::VectorXd force = internal_forces(p, r, u);
    if (n == 1) {
      k_one = p.stiffness.values;
      fused_one = fused;
      force_one = force;
      // Oracle: the same sums through an Eigen sparse matrix of triplets, element by element.
      std::vector<Eigen::Triplet<double>> triplets;
      Eigen::VectorXd f0_oracle = Eigen::VectorXd::Zero(p.num_dofs());
      for (int e = 0; e < p.mesh.num_tets(); ++e) {
        const Mat12 ke = test::dense_element_stiffness(p, e);
        for (int a = 0; a < 4; ++a) {
          for (int b = 0; b < 4; ++b)  // f0_e = Q K_e x_e
            f0_oracle.segment<3>(3 * p.mesh.tets[e][a]) +=
                r[e] * (ke.block<3, 3>(3 * a, 3 * b) * p.mesh.rest[p.mesh.tets[e][b]]);
          for (int b = 0; b < 4; ++b) {
            const Mat3 blk = r[e] * ke.block<3, 3>(3 * a, 3 * b) * r[e].transpose();
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                triplets.emplace_back(3 * p.mesh.tets[e][a] + i, 3 * p.mesh.tets[e][b] + j,
                                      blk(i, j));
          }
        }
      }
      Eigen::SparseMatrix<double> k(p.num_dofs(), p.num_dofs());
      k.setFromTriplets(triplets.begin(), triplets.end());
      // Summation order differs from the oracle's: a few ulps of the largest entry.
      const Eigen::SparseMatrix<double> ours = to_eigen(p.stiffness);
      EXPECT_LT((Eigen::MatrixXd(ours) - Eigen::MatrixXd(k)).norm(),
                1e-13 * Eigen::MatrixXd(k).norm());
      // Ktilde p - f0 is the force (cancellation: |K||x| / |f| ~ 1e3 here, so 1e-9 relative).
      Eigen::VectorXd positions(p.num_dofs());
      for (int v = 0; v < p.mesh.num_vertices(); ++v) positions.segment<3>(3 * v) = x[v];
      EXPECT_LT((ours * positions - f0_oracle - force).norm(), 1e-9 * force.norm());
      EXPECT_LT((ours * positions - f0_oracle - fused).norm(), 1e-9 * force.norm());
      // Both kernels from the same strains, K_e s from K_e's columns or from the gradients:
      // round-off of the element forces, |K_e||s| ~ 10 |f| here.
      EXPECT_LT((fused - force).norm(), 1e-12 * force.norm());
    }
    EXPECT_TRUE(same_bits(p.stiffness.values, k_one)) << n << " threads";
    EXPECT_TRUE(same_bits(fused, fused_one)) << n << " threads";
    EXPECT_TRUE(same_bits(force, force_one)) << n << " threads";
    // Each element is visited once per part owning one of its vertices: the duplication is the
    // partition boundary's share, small on a locality-ordered mesh.
    if (n > 1) {
      EXPECT_LT(p.assembly.rows.duplication(), 0.25) << n << " threads";
    }
  }
}

TEST_F(ThreadsTest, StreamProductIsTheOneThreadBitsAndTheOracle) {
  SceneSimulation sim = quadruped(0.12);
  FeProblem& p = sim.problem();
  const BrcMatrix a = random_symmetric(p.stiffness, 5);
  SceneSimulation coarse_sim = quadruped(0.24);
  const TetMesh& coarse = coarse_sim.problem().mesh;
  const Transfer t =
      make_mesh_level(p.mesh.rest, std::vector<char>(p.mesh.rest.size(), 0), coarse, "coarse")
          .transfer;
  const BrcMatrix pattern = galerkin_pattern(a, t);
  const Eigen::SparseMatrix<double> r = restriction_matrix(t);
  const Eigen::MatrixXd oracle =
      reference::dense_galerkin(Eigen::MatrixXd(r), Eigen::MatrixXd(to_eigen(a)));
  std::vector<double> one;
  for (const auto symmetry : {GalerkinStream::Symmetry::Symmetric, GalerkinStream::Symmetry::Full})
    for (const int n : kThreadCounts) {
      ScopedThreadCount threads(n);
      const GalerkinStream stream(a, t, pattern, symmetry, n);
      ASSERT_EQ(stream.parts(), n);
      BrcMatrix e = pattern;
      stream.apply(a, e);
      if (n == 1) {
        one = e.values;
        EXPECT_LT((Eigen::MatrixXd(to_eigen(e)) - oracle).norm(), 1e-13 * oracle.norm());
      }
      EXPECT_TRUE(same_bits(e.values, one)) << n << " threads";
    }
}

TEST_F(ThreadsTest, EveryGalerkinMethodIsTheOneThreadBitsOnEveryLevel) {
  // A three-level hierarchy of non-nested quadrupeds under a random symmetric fine matrix: every
  // method's coarse operators on every level, the same bits at every count (each method's own
  // bits: the methods sum in different orders). Their values against the dense oracle:
  // multigrid_galerkin_test.cpp.
  SceneSimulation sim = quadruped(0.12);
  FeProblem& p = sim.problem();
  const BrcMatrix a = random_symmetric(p.stiffness, 7);
  SceneSimulation coarse_sim = quadruped(0.24), coarsest_sim = quadruped(0.4);
  const CoarseLevel first = make_mesh_level(p.mesh.rest, std::vector<char>(p.mesh.rest.size(), 0),
                                            coarse_sim.problem().mesh, "coarse");
  const CoarseLevel second =
      make_mesh_level(first.points, std::vector<char>(first.points.size(), 0),
                      coarsest_sim.problem().mesh, "coarsest");
  for (const char* name : {"naive", "stream", "stream-full", "reuse", "gather"}) {
    SCOPED_TRACE(name);
    std::vector<std::vector<double>> one;
    for (const int n : kThreadCounts) {
      ScopedThreadCount threads(n);
      MultigridHierarchy hierarchy(a, {first.transfer, second.transfer});
      ASSERT_EQ(hierarchy.num_levels(), 3);
      hierarchy.update(a, *kGalerkinMethods.find(name));
      hierarchy.update(a, *kGalerkinMethods.find(name));  // reuse's second differs from its first
      for (int h = 1; h < hierarchy.num_levels(); ++h) {
        if (n == 1) one.push_back(hierarchy.matrix(h).values);
        EXPECT_TRUE(same_bits(hierarchy.matrix(h).values, one[h - 1]))
            << "level " << h << " at " << n << " threads";
      }
    }
  }
}

/// A smoother's test system: the quadruped's small-strain K + M/dt^2 (as a dynamic step's
/// matrix), a right-hand side, and its dense form and exact solution (the oracles).
struct SmootherSystem {
  BrcMatrix a;
  Eigen::VectorXd b;
  Eigen::MatrixXd dense;
  Eigen::VectorXd exact;
};

SmootherSystem smoother_system() {
  SceneSimulation sim = quadruped(0.12);
  FeProblem& p = sim.problem();
  const std::vector<Mat3> identity(p.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd force;
  assemble_corotated(p.elements, p.mesh, p.assembly, identity, Eigen::VectorXd::Zero(p.num_dofs()),
                     p.stiffness, force);
  SmootherSystem s{p.stiffness, {}, {}, {}};
  for (int i = 0; i < s.a.block_rows; ++i)
    s.a.block(s.a.find(i, i)) += 1e3 * Mat3::Identity();  // + M/dt^2
  s.b = Eigen::VectorXd::LinSpaced(3 * s.a.block_rows, -1, 1);
  s.dense = Eigen::MatrixXd(to_eigen(s.a));
  s.exact = s.dense.ldlt().solve(s.b);
  return s;
}

/// The A-norm squared of x's error.
double error_energy(const SmootherSystem& s, const Eigen::VectorXd& x) {
  const Eigen::VectorXd err = s.exact - x;
  return err.dot(s.dense * err);
}

TEST_F(ThreadsTest, ParallelSmoothersAreTheSameBitsAtEveryCountAndSmooth) {
  const SmootherSystem system = smoother_system();
  const BrcMatrix& a = system.a;
  const Eigen::VectorXd& b = system.b;
  const Eigen::MatrixXd& dense = system.dense;
  const Eigen::VectorXd& exact = system.exact;
  // Domains of 200 rows: this small mesh gets several, with boundaries between them.
  for (const SmootherOrdering ordering :
       {SmootherOrdering::Multicolour, SmootherOrdering::Domains}) {
    SCOPED_TRACE(kSmootherOrderings.name(ordering));
    Eigen::VectorXd one;
    for (const int n : kThreadCounts) {
      ScopedThreadCount threads(n);
      BlockGaussSeidel gs(ordering, 200);
      gs.set_matrix(a);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
      double previous = exact.dot(dense * exact);
      for (int s = 0; s < 4; ++s) {
        gs.forward(a, b, x);
        gs.backward(a, b, x);
        // Symmetric Gauss-Seidel reduces the A-norm of the error, whatever the order.
        const double energy = error_energy(system, x);
        EXPECT_LT(energy, previous);
        previous = energy;
      }
      if (n == 1) one = x;
      EXPECT_TRUE(same_bits(x, one)) << n << " threads";
      // Each tet's four vertices are coupled pairwise (a 4-clique of blocks), so a proper
      // colouring needs at least 4 colours. Domains colours its boundary rows only, and a tet
      // straddling two domains has all four vertices on the boundary: 4 there too.
      EXPECT_GE(gs.num_colours(), 4);
      EXPECT_LT(gs.num_colours(), 64);
      if (ordering == SmootherOrdering::Domains) {
        EXPECT_EQ(gs.num_domains(), a.block_rows / 200);
        EXPECT_LT(gs.coloured_rows(), a.block_rows);  // most rows are interior to their domain
        EXPECT_GT(gs.coloured_rows(), 0);
      } else {
        EXPECT_EQ(gs.coloured_rows(), a.block_rows);
      }
    }
  }
}

/// M^-1 r (or M^-T r when `transposed`) for M block lower triangular with 3x3 blocks, by block
/// substitution on the dense matrix. (No Eigen factorization of a dynamic matrix here: in the
/// sanitizer build its template instance would interpose libgmsh's own, built with another
/// allocator.)
Eigen::VectorXd block_triangular_solve(const Eigen::MatrixXd& m, const Eigen::VectorXd& r,
                                       bool transposed) {
  const int n = static_cast<int>(r.size()) / 3;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(r.size());
  for (int step = 0; step < n; ++step) {
    const int i = transposed ? n - 1 - step : step;
    Eigen::Vector3d rhs = r.segment<3>(3 * i);
    for (int j = 0; j < n; ++j) {
      if (j == i || (transposed ? j < i : j > i)) continue;
      const Eigen::Matrix3d block = transposed
                                        ? Eigen::Matrix3d(m.block<3, 3>(3 * j, 3 * i).transpose())
                                        : Eigen::Matrix3d(m.block<3, 3>(3 * i, 3 * j));
      rhs -= block * y.segment<3>(3 * j);
    }
    const Eigen::Matrix3d diagonal = transposed
                                         ? Eigen::Matrix3d(m.block<3, 3>(3 * i, 3 * i).transpose())
                                         : Eigen::Matrix3d(m.block<3, 3>(3 * i, 3 * i));
    y.segment<3>(3 * i) = diagonal.inverse() * rhs;
  }
  return y;
}

TEST_F(ThreadsTest, HybridSmootherIsItsDenseSplittingAtEveryCount) {
  // Oracle: a forward sweep is x + M^-1 (b - A x) with M = D + D_l1 + L_domains built densely
  // (D the diagonal blocks, L_domains the lower blocks inside a domain, D_l1 per scalar row the
  // sum of |A| outside its domain); a backward sweep the same with M^T.
  const SmootherSystem system = smoother_system();
  const BrcMatrix& a = system.a;
  const Eigen::VectorXd& b = system.b;
  const Eigen::MatrixXd& dense = system.dense;
  const Eigen::VectorXd& exact = system.exact;
  const int domain_blocks = static_cast<int>(a.num_blocks() / 5);  // 5 domains, made 6
  BlockGaussSeidel layout(SmootherOrdering::Hybrid, domain_blocks);
  layout.set_matrix(a);
  ASSERT_EQ(layout.num_domains(), 6);
  EXPECT_GT(layout.boundary_rows(), 0);
  EXPECT_LT(layout.boundary_rows(), a.block_rows);
  std::vector<int> domain_of(3 * a.block_rows);
  for (int d = 0; d < layout.num_domains(); ++d)
    for (int i = layout.domain_rows_begin(d); i < layout.domain_rows_begin(d + 1); ++i)
      for (int c = 0; c < 3; ++c) domain_of[3 * i + c] = d;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(dense.rows(), dense.cols());
  for (int r = 0; r < dense.rows(); ++r)
    for (int c = 0; c < dense.cols(); ++c) {
      if (domain_of[c] != domain_of[r])
        m(r, r) += std::abs(dense(r, c));
      else if (c / 3 <= r / 3)
        m(r, c) += dense(r, c);
    }
  test::in_each_kernel_form([&] {
    Eigen::VectorXd one;
    for (const int n : kThreadCounts) {
      ScopedThreadCount threads(n);
      BlockGaussSeidel gs(SmootherOrdering::Hybrid, domain_blocks);
      gs.set_matrix(a);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
      double previous = exact.dot(dense * exact);
      for (int s = 0; s < 3; ++s) {
        Eigen::VectorXd expected = x + block_triangular_solve(m, b - dense * x, false);
        gs.forward(a, b, x);
        EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "forward sweep " << s;
        expected = x + block_triangular_solve(m, b - dense * x, true);
        gs.backward(a, b, x);
        EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "backward sweep " << s;
        // M + M^T - A = D + 2 D_l1 - A_off is positive definite: the A-norm of the error falls.
        const double energy = error_energy(system, x);
        EXPECT_LT(energy, previous);
        previous = energy;
      }
      if (n == 1) one = x;
      EXPECT_TRUE(same_bits(x, one)) << n << " threads";
    }
    // One domain: exactly the sequential smoother.
    BlockGaussSeidel hybrid(SmootherOrdering::Hybrid, static_cast<int>(a.num_blocks()) + 1),
        sequential;
    hybrid.set_matrix(a);
    sequential.set_matrix(a);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), y = x;
    hybrid.forward(a, b, x);
    hybrid.backward(a, b, x);
    sequential.forward(a, b, y);
    sequential.backward(a, b, y);
    EXPECT_EQ(hybrid.num_domains(), 1);
    EXPECT_TRUE(same_bits(x, y));
  });
}

TEST_F(ThreadsTest, ForwardSweepFromZeroIsTheFullSweepAndReadsOnlyTheLowerBlocks) {
  // A V-cycle's first sweep of a correction: forward_from_zero must give exactly the bits of
  // x = 0 followed by forward(), whatever x held, at every thread count. For the sequential and
  // hybrid orderings it may read only the blocks below the diagonal (inside its domain): the same
  // matrix with every other off-diagonal block made NaN must give the same bits.
  const SmootherSystem system = smoother_system();
  const BrcMatrix& a = system.a;
  const Eigen::VectorXd& b = system.b;
  const int domain_blocks = static_cast<int>(a.num_blocks() / 5);
  test::in_each_kernel_form([&] {
    for (const SmootherOrdering ordering :
         {SmootherOrdering::Sequential, SmootherOrdering::Multicolour, SmootherOrdering::Domains,
          SmootherOrdering::Hybrid}) {
      SCOPED_TRACE(kSmootherOrderings.name(ordering));
      const bool lower_only =
          ordering == SmootherOrdering::Sequential || ordering == SmootherOrdering::Hybrid;
      for (const int n : kThreadCounts) {
        ScopedThreadCount threads(n);
        BlockGaussSeidel gs(ordering, ordering == SmootherOrdering::Domains ? 200 : domain_blocks);
        gs.set_matrix(a);
        Eigen::VectorXd expected = Eigen::VectorXd::Zero(b.size());
        gs.forward(a, b, expected);
        Eigen::VectorXd x = Eigen::VectorXd::Constant(b.size(), std::nan(""));
        gs.forward_from_zero(a, b, x);
        EXPECT_TRUE(same_bits(x, expected)) << n << " threads";
        if (!lower_only) continue;
        // The sequential ordering is one domain of all rows.
        const bool hybrid = ordering == SmootherOrdering::Hybrid;
        const int domains = hybrid ? gs.num_domains() : 1;
        const auto begin = [&](int d) {
          return hybrid ? gs.domain_rows_begin(d) : d * a.block_rows;
        };
        BrcMatrix poisoned = a;
        int kept = 0;
        for (int d = 0; d < domains; ++d)
          for (int i = begin(d); i < begin(d + 1); ++i)
            for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
              const int j = a.col_index[k];
              if (j < i && j >= begin(d)) {
                ++kept;
                continue;
              }
              if (j != i) poisoned.block(k).setConstant(std::nan(""));
            }
        EXPECT_LT(2 * kept, a.num_blocks());
        Eigen::VectorXd y;
        gs.forward_from_zero(poisoned, b, y);
        EXPECT_TRUE(same_bits(y, expected)) << n << " threads, upper blocks poisoned";
      }
    }
  });
}

TEST_F(ThreadsTest, SweepFromZeroWithResidualIsTheSweepAndItsResidual) {
  // The V-cycle's pre-smoothing with its residual in one pass: x must be forward_from_zero's
  // bits, r = b - A x to round-off, the same bits at every thread count. The two residuals sum
  // in different orders, after the sweep's own arithmetic (a 3x3 inverse applied to a sum of some
  // 30 terms): a few hundred ulps of |b| + |A| |x| at most. A term left out (a domain's halo, a
  // transposed block) is of the size of the product's entries: far above that.
  const SmootherSystem system = smoother_system();
  const BrcMatrix& a = system.a;
  const Eigen::VectorXd& b = system.b;
  BrcMatrix abs_a = a;
  for (double& v : abs_a.values) v = std::abs(v);
  const int domain_blocks = static_cast<int>(a.num_blocks() / 5);
  test::in_each_kernel_form([&] {
    for (const SmootherOrdering ordering :
         {SmootherOrdering::Sequential, SmootherOrdering::Multicolour, SmootherOrdering::Domains,
          SmootherOrdering::Hybrid}) {
      SCOPED_TRACE(kSmootherOrderings.name(ordering));
      Eigen::VectorXd first_r;
      for (const int n : kThreadCounts) {
        ScopedThreadCount threads(n);
        BlockGaussSeidel gs(ordering, ordering == SmootherOrdering::Domains ? 200 : domain_blocks);
        gs.set_matrix(a);
        if (ordering == SmootherOrdering::Hybrid) {
          EXPECT_GT(gs.num_domains(), 2);
        }
        Eigen::VectorXd x, expected_x, r, full;
        gs.forward_from_zero(a, b, expected_x);
        x = Eigen::VectorXd::Constant(b.size(), std::nan(""));
        gs.forward_from_zero_with_residual(a, b, x, r);
        EXPECT_TRUE(same_bits(x, expected_x)) << n << " threads";
        a.residual(b, x, full);
        const Eigen::ArrayXd scale = (b.cwiseAbs() + abs_a * x.cwiseAbs()).array();
        EXPECT_LT(((r - full).cwiseAbs().array() / scale).maxCoeff(), 1e-13) << n << " threads";
        EXPECT_GT((full.cwiseAbs().array() / scale).maxCoeff(), 1e-3)
            << "a residual that is not round-off";
        if (first_r.size() == 0) first_r = r;
        EXPECT_TRUE(same_bits(r, first_r)) << n << " threads";
      }
    }
  });
}

TEST_F(ThreadsTest, SideBySideRunsBothAndRethrowsAfterBoth) {
  for (const int n : kThreadCounts) {
    ScopedThreadCount threads(n);
    // Each task's own parallel loop still covers its range (on its one thread when side by side).
    std::vector<int> left(5000, 0), right(5000, 0);
    run_side_by_side(
        [&] {
#pragma omp parallel for num_threads(threads_for(5000))
          for (int i = 0; i < 5000; ++i) left[i] = i;
        },
        [&] {
#pragma omp parallel for num_threads(threads_for(5000))
          for (int i = 0; i < 5000; ++i) right[i] = 2 * i;
        });
    for (int i = 0; i < 5000; ++i)
      ASSERT_TRUE(left[i] == i && right[i] == 2 * i) << n << " threads, " << i;
    // A failure in either comes out after both ran, the first task's first.
    bool b_ran = false;
    EXPECT_THROW(run_side_by_side([] { throw NumericalFault("a"); }, [&] { b_ran = true; }),
                 NumericalFault);
    EXPECT_TRUE(b_ran) << n << " threads";
    try {
      run_side_by_side([] { throw InputError("a"); }, [] { throw NumericalFault("b"); });
      ADD_FAILURE() << "no exception";
    } catch (const InputError&) {
    }
  }
}

TEST_F(ThreadsTest, DynamicRunIsBitIdenticalAtEveryThreadCountAndRunToRun) {
  for (const std::string smoother : {"multicolour", "domains", "hybrid", "sequential"}) {
    Eigen::VectorXd one;
    for (const int n : {1, 2, 3, 2}) {  // 2 twice: run to run
      ScopedThreadCount threads(n);
      SceneSimulation sim = quadruped(0.12, smoother);
      const SimulationResult result = sim.run();
      if (one.size() == 0) one = result.displacement;
      EXPECT_TRUE(same_bits(result.displacement, one)) << smoother << " at " << n << " threads";
      EXPECT_GT(result.displacement.norm(), 0);
    }
  }
}

TEST_F(ThreadsTest, NewtonSolvesAreBitIdenticalAtEveryThreadCount) {
  // Newton on the static equilibrium and on fully implicit Euler (the consistent tangent and a
  // sparse LU, which Newton uses whatever the scene's solver): the rotations, the tangent's
  // assembly, the forces and every Newton update the same bits at every count.
  for (const std::string type : {"static", "dynamic"}) {
    for (const std::string rotation : {"energy-newton", "polar"}) {
      Eigen::VectorXd one;
      for (const int n : kThreadCounts) {
        ScopedThreadCount threads(n);
        // A 20 x 2 x 2 cantilever clamped at x = 0, sagging under gravity. (The quadruped, held by
        // two feet, swings far from rest under a static load: Newton's full steps diverge there.)
        const nlohmann::json scene = {
            {"mesh", {{"box", {2.0, 0.2, 0.2}}, {"cells", {20, 2, 2}}}},
            {"material", {{"young", 1e6}, {"poisson", 0.3}, {"density", 1000}}},
            {"fixed", {{{"box", {{0, 0, 0}, {0, 0.2, 0.2}}}}}},
            {"gravity", {0, 0, -9.81}},
            {"analysis",
             {{"type", type},
              {"integrator", "newton"},
              {"rotation", rotation},
              {"solver", "mgpcg"},
              {"smoother", "hybrid"},
              {"levels", 2},
              {"dt", 0.01},
              {"steps", 3},
              {"load_steps", 2},
              {"tolerance", 1e-8}}}};
        SceneSimulation sim(parse_scene(scene, ".", "threads"));
        const SimulationResult result = sim.run();
        ASSERT_TRUE(result.converged)
            << type << " " << rotation << " at " << n << " threads: " << result.message;
        if (n == 1) one = result.displacement;
        EXPECT_TRUE(same_bits(result.displacement, one))
            << type << " " << rotation << " at " << n << " threads";
        EXPECT_GT(result.displacement.norm(), 0);
      }
    }
  }
}

TEST_F(ThreadsTest, CliRefusesABadThreadCount) {
  for (const char* bad : {"0", "many", "-2"}) {
    const auto r = test::run_cli(std::string("run nothing.json --out x.json --threads ") + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace corofem
