// Corotated assembly and internal forces: rigid invariance, rotation equivariance, and the BRC
// assembly against an Eigen matrix built from triplets.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <limits>
#include <random>

#include "fem/corotated_assembly.hpp"
#include "fem/fe_problem.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/polar_decomposition.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

FeProblem small_box() {
  TetMesh mesh = make_box_mesh({1.0, 0.5, 0.3}, {4, 3, 2});
  std::vector<Material> m(mesh.tets.size(), Material{1e5, 0.35, 1000});
  return make_fe_problem(std::move(mesh), std::move(m));
}

std::vector<Mat3> polar_rotations(const FeProblem& p, const std::vector<Vec3>& positions) {
  PolarExtractor polar(p.mesh);
  std::vector<Mat3> r(p.mesh.tets.size(), Mat3::Identity());
  polar.extract(positions, r);
  return r;
}

Eigen::VectorXd displacement(const FeProblem& p, const std::vector<Vec3>& positions) {
  Eigen::VectorXd u(p.num_dofs());
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    u.segment<3>(3 * v) = positions[v] - p.mesh.rest[v];
  return u;
}

TEST(CorotatedAssembly, RigidMotionGivesZeroForce) {
  FeProblem p = small_box();
  std::mt19937 rng(7);
  double scale = 0;  // force scale: |K_e| times the mesh size
  for (int e = 0; e < p.mesh.num_tets(); ++e)
    scale = std::max(scale, test::dense_element_stiffness(p, e).norm());
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 r = random_rotation(rng);
    const Vec3 t(3, -2, 5);
    std::vector<Vec3> moved(p.mesh.rest.size());
    for (std::size_t v = 0; v < moved.size(); ++v) moved[v] = r * p.mesh.rest[v] + t;
    const auto rotations = polar_rotations(p, moved);
    const Eigen::VectorXd f = internal_forces(p, rotations, displacement(p, moved));
    // Forces are K (Q^T p - x) with Q^T p - x = O(eps * |x|): relative 1e-12 of |K| |x|.
    EXPECT_LT(f.lpNorm<Eigen::Infinity>(), 1e-12 * scale * 6.0) << "trial " << trial;
    // The assembly's force (from K_e's columns instead of the gradients) too, in both forms.
    test::in_each_kernel_form([&] {
      Eigen::VectorXd fused;
      assemble_corotated(p.elements, p.mesh, p.assembly, rotations, displacement(p, moved),
                         p.stiffness, fused);
      EXPECT_LT(fused.lpNorm<Eigen::Infinity>(), 1e-12 * scale * 6.0) << "trial " << trial;
    });
  }
}

TEST(CorotatedAssembly, ForcesAreRotationEquivariant) {
  FeProblem p = small_box();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  std::vector<Vec3> deformed(p.mesh.rest.size());
  for (std::size_t v = 0; v < deformed.size(); ++v)
    deformed[v] = p.mesh.rest[v] + Vec3(u(rng), u(rng), u(rng)) +
                  0.3 * Vec3(p.mesh.rest[v].y(), -p.mesh.rest[v].x(), 0.1);
  const Eigen::VectorXd f =
      internal_forces(p, polar_rotations(p, deformed), displacement(p, deformed));
  const Mat3 r = random_rotation(rng);
  std::vector<Vec3> rotated(deformed.size());
  for (std::size_t v = 0; v < deformed.size(); ++v) rotated[v] = r * deformed[v] + Vec3(1, 2, 3);
  const Eigen::VectorXd g =
      internal_forces(p, polar_rotations(p, rotated), displacement(p, rotated));
  double worst = 0;
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    worst = std::max(worst, (g.segment<3>(3 * v) - r * f.segment<3>(3 * v)).norm());
  EXPECT_LT(worst, 1e-12 * f.lpNorm<Eigen::Infinity>());
}

TEST(BrcAssembly, EqualsEigenTripletAssemblyAndSpmvInBothForms) {
  FeProblem p = small_box();
  std::mt19937 rng(3);
  std::vector<Mat3> rotations(p.mesh.tets.size());
  for (auto& q : rotations) q = random_rotation(rng);
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  Eigen::VectorXd u(p.num_dofs());
  for (int i = 0; i < u.size(); ++i) u[i] = d(rng);
  // Oracle: dense 12x12 Q K Q^T per element scattered as triplets, and the force
  // Ktilde_e p_e - f0_e = Q K_e (Q^T p_e - x_e) as dense products.
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd force_ref = Eigen::VectorXd::Zero(p.num_dofs());
  for (int e = 0; e < p.mesh.num_tets(); ++e) {
    Mat12 q = Mat12::Zero();
    for (int a = 0; a < 4; ++a) q.block<3, 3>(3 * a, 3 * a) = rotations[e];
    const Mat12 kt = q * test::dense_element_stiffness(p, e) * q.transpose();
    Vec12 x, pe;
    for (int a = 0; a < 4; ++a) {
      x.segment<3>(3 * a) = p.mesh.rest[p.mesh.tets[e][a]];
      pe.segment<3>(3 * a) = x.segment<3>(3 * a) + u.segment<3>(3 * p.mesh.tets[e][a]);
    }
    const Vec12 fe = q * (test::dense_element_stiffness(p, e) * (q.transpose() * pe - x));
    for (int a = 0; a < 4; ++a) {
      force_ref.segment<3>(3 * p.mesh.tets[e][a]) += fe.segment<3>(3 * a);
      for (int b = 0; b < 4; ++b)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            triplets.emplace_back(3 * p.mesh.tets[e][a] + r, 3 * p.mesh.tets[e][b] + c,
                                  kt(3 * a + r, 3 * b + c));
    }
  }
  Eigen::SparseMatrix<double> ref(p.num_dofs(), p.num_dofs());
  ref.setFromTriplets(triplets.begin(), triplets.end());
  test::in_each_kernel_form([&] {
    Eigen::VectorXd force;
    // K is not zeroed first: each block's lowest-numbered element stores, the others add. NaN
    // in every entry beforehand shows a block no element wrote, or one added to a stale value.
    std::fill(p.stiffness.values.begin(), p.stiffness.values.end(),
              std::numeric_limits<double>::quiet_NaN());
    assemble_corotated(p.elements, p.mesh, p.assembly, rotations, u, p.stiffness, force);
    const Eigen::SparseMatrix<double> ours = to_eigen(p.stiffness);
    // Same sums in a different order: round-off of a few ulps of |K|.
    EXPECT_LT((ours - ref).norm(), 1e-14 * ref.norm());
    // The oracle forms Q^T p - x, cancelling terms of |x| ~ 1 to a strain of ~0.1 (random Q):
    // its round-off, and the kernel's, are some ulps of |K_e| |x|, 1e-13 of |f| here.
    EXPECT_LT((force - force_ref).norm(), 1e-12 * force_ref.norm());
    // A time step's matrix, scale Ktilde + diag(d), written straight into another matrix: the
    // scale multiplies V lambda and V mu, so the blocks are the scaled ones to round-off, and d
    // is added once per DOF (d of the size of the scaled diagonal, as a mass is); the force is
    // neither (the same bits).
    const double scale = 2.5e-4;
    const Eigen::VectorXd d = scale * ref.diagonal().cwiseAbs().maxCoeff() *
                              Eigen::VectorXd::LinSpaced(p.num_dofs(), 1.0, 2.0);
    Eigen::SparseMatrix<double> expected = scale * ref;
    for (int i = 0; i < p.num_dofs(); ++i) expected.coeffRef(i, i) += d[i];
    BrcMatrix scaled = p.stiffness;
    std::fill(scaled.values.begin(), scaled.values.end(), std::numeric_limits<double>::quiet_NaN());
    Eigen::VectorXd scaled_force;
    assemble_corotated(p.elements, p.mesh, p.assembly, rotations, u, scaled, scaled_force, scale,
                       &d);
    EXPECT_LT((to_eigen(scaled) - expected).norm(), 1e-14 * expected.norm());
    EXPECT_EQ((scaled_force - force).cwiseAbs().maxCoeff(), 0.0);
    Eigen::VectorXd x = Eigen::VectorXd::Random(p.num_dofs());
    const Eigen::VectorXd y_ref = ref * x;
    EXPECT_LT((p.stiffness * x - y_ref).norm(), 1e-14 * ref.norm() * x.norm());
    // Off the diagonal exactly symmetric: block (j, i) is block (i, j) transposed, bit for bit
    // (each element's pair is rotated once). The diagonal blocks Q K_aa Q^T are symmetric only
    // to round-off, in both forms.
    for (int i = 0; i < p.stiffness.block_rows; ++i)
      for (int k = p.stiffness.row_start[i]; k < p.stiffness.row_start[i + 1]; ++k) {
        const int j = p.stiffness.col_index[k];
        if (j == i) continue;
        ASSERT_TRUE(p.stiffness.block(k) == p.stiffness.block(p.stiffness.find(j, i)).transpose())
            << "block (" << i << ", " << j << ")";
      }
  });
}

TEST(CorotatedAssembly, InternalForcesEqualTheDenseElementSum) {
  // Oracle: f = sum_e Q_e K_e (Q_e^T p_e - x_e) with the dense 12x12 K_e of element_stiffness
  // (the kernel builds K_e s from the shape gradients instead), random rotations and positions.
  FeProblem p = small_box();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::vector<Vec3> moved(p.mesh.rest.size());
  for (std::size_t v = 0; v < moved.size(); ++v)
    moved[v] = p.mesh.rest[v] + Vec3(u(rng), u(rng), u(rng));
  std::vector<Mat3> rotations(p.mesh.tets.size());
  for (auto& q : rotations) q = random_rotation(rng);
  const Eigen::VectorXd f = internal_forces(p, rotations, displacement(p, moved));
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(p.num_dofs());
  for (int e = 0; e < p.mesh.num_tets(); ++e) {
    const Tet& t = p.mesh.tets[e];
    Vec12 s;
    for (int a = 0; a < 4; ++a)
      s.segment<3>(3 * a) = rotations[e].transpose() * moved[t[a]] - p.mesh.rest[t[a]];
    const Vec12 local = test::dense_element_stiffness(p, e) * s;
    for (int a = 0; a < 4; ++a)
      expected.segment<3>(3 * t[a]) += rotations[e] * local.segment<3>(3 * a);
  }
  // The same forces summed in another order (and s shifted by a translation K_e annihilates):
  // round-off relative to the element forces' size, |K_e| |p| ~ 1e2 times |f| here: 1e-12.
  EXPECT_LT((f - expected).norm(), 1e-12 * expected.norm());
  EXPECT_GT(expected.norm(), 0);
}

TEST(BrcMatrix, FindReturnsMinusOneOutsidePattern) {
  FeProblem p = small_box();
  EXPECT_GE(p.stiffness.find(0, 0), 0);
  EXPECT_EQ(p.stiffness.find(0, p.mesh.num_vertices() - 1), -1);
  for (int e = 0; e < p.mesh.num_tets(); ++e)
    for (int a = 0; a < 16; ++a) ASSERT_GE(p.assembly.block[e][a], 0);
}

}  // namespace
}  // namespace corofem
