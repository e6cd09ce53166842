// Dirichlet conditions: the symmetric elimination gives the solution of the reduced system, and
// CHOLMOD agrees with Eigen's dense LDLT (two independent factorizations).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>

#include "cholmod_oracle.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/dirichlet.hpp"
#include "fem/fe_problem.hpp"
#include "mesh/box_mesh.hpp"
#include "sparse/brc_to_eigen.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

TEST(Dirichlet, EliminationEqualsReducedDenseSolve) {
  TetMesh mesh = make_box_mesh({1, 1, 1}, {3, 3, 3});
  std::vector<Material> m(mesh.tets.size(), Material{1e3, 0.3, 1});
  FeProblem p = make_fe_problem(std::move(mesh), std::move(m));
  std::vector<Mat3> identity(p.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd force;
  assemble_corotated(p.elements, p.mesh, p.assembly, identity, Eigen::VectorXd::Zero(p.num_dofs()),
                     p.stiffness, force);
  const Eigen::MatrixXd k = Eigen::MatrixXd(to_eigen(p.stiffness));
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v].z() < 1e-12) p.dirichlet.fix_vertex(v, Vec3(0.01 * v, -0.02, 0.003 * v));
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(p.num_dofs(), -1, 1);
  BrcMatrix a = p.stiffness;
  Eigen::VectorXd b = f;
  apply_dirichlet(p.dirichlet, a, b);
  const Eigen::SparseMatrix<double> ae = to_eigen(a);
  EXPECT_LT((Eigen::MatrixXd(ae) - Eigen::MatrixXd(ae).transpose()).norm(), 1e-15 * k.norm());
  const Eigen::VectorXd x = reference::cholmod_solve(ae, b);
  // Reduced dense oracle: K_ff x_f = f_f - K_fc g.
  std::vector<int> free, fixed;
  for (int d = 0; d < p.num_dofs(); ++d) (p.dirichlet.fixed[d] ? fixed : free).push_back(d);
  Eigen::MatrixXd kff(free.size(), free.size());
  Eigen::VectorXd rhs(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) {
    rhs[i] = f[free[i]];
    for (int c : fixed) rhs[i] -= k(free[i], c) * p.dirichlet.value[c];
    for (std::size_t j = 0; j < free.size(); ++j) kff(i, j) = k(free[i], free[j]);
  }
  const Eigen::VectorXd xf = kff.ldlt().solve(rhs);
  // K is well conditioned here (cond ~1e3): both solves agree to ~1e-13.
  for (std::size_t i = 0; i < free.size(); ++i)
    EXPECT_NEAR(x[free[i]], xf[i], 1e-10 * xf.lpNorm<Eigen::Infinity>());
  for (int c : fixed) EXPECT_EQ(x[c], p.dirichlet.value[c]);
}

TEST(Dirichlet, EliminationIsTheDenseOneBitForBitWithSomeDofsOfAVertexFixed) {
  // apply_dirichlet visits only the rows and columns of supported vertices; the dense form below
  // visits every entry, each row's columns in ascending order. Same operations in the same
  // order: the same bits, also where a vertex has only some DOFs fixed.
  std::mt19937 rng(3);
  BrcMatrix a = test::random_spd_brc(40, rng);
  DirichletConditions bc = DirichletConditions::none(3 * a.block_rows);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int d = 0; d < 3 * a.block_rows; d += 7) {  // every 7th DOF: vertices with 1 of 3 fixed
    bc.fixed[d] = 1;
    bc.value[d] = u(rng);
  }
  bc.fix_vertex(5, {0.1, -0.2, 0.3});
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * a.block_rows, -1, 1);
  Eigen::MatrixXd dense = test::dense_copy(a);
  Eigen::VectorXd dense_b = b;
  for (int row = 0; row < dense.rows(); ++row)
    for (int col = 0; col < dense.cols(); ++col) {
      if (dense(row, col) == 0 && row != col)
        continue;  // outside the pattern (no entry is 0 inside)
      if (!bc.fixed[row] && bc.fixed[col]) dense_b[row] -= dense(row, col) * bc.value[col];
      if (bc.fixed[row] || bc.fixed[col]) dense(row, col) = row == col ? 1.0 : 0.0;
    }
  for (int d = 0; d < dense.rows(); ++d)
    if (bc.fixed[d]) dense_b[d] = bc.value[d];
  BrcMatrix matrix_only = a;  // the matrix-only form: the same A
  apply_dirichlet(bc, a, b);
  EXPECT_EQ((test::dense_copy(a) - dense).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(std::memcmp(b.data(), dense_b.data(), sizeof(double) * b.size()) == 0);
  apply_dirichlet_to_matrix(bc, matrix_only);
  EXPECT_EQ(matrix_only.values, a.values);
}

}  // namespace
}  // namespace corofem
