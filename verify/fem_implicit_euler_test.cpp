// Implicit Euler: a damped cantilever comes to rest at the static solution of the same
// formulation (the static solver is the oracle); small strain with moving supports against the
// same Euler written densely; rigid free fall against its exact trajectory.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "cantilever_fixture.hpp"
#include "fem/corotated_assembly.hpp"
#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "rotation/rotation_extractor.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {
namespace {

using test::Cantilever;

class DampedSettling : public ::testing::TestWithParam<bool> {};

TEST_P(DampedSettling, ComesToRestAtStaticSolution) {
  const bool corotational = GetParam();
  const Cantilever bar;
  FeProblem p = bar.build(1, corotational ? 3.0 : 1.0);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  auto solver = make_cholmod_solver();
  const SimulationResult s = solve_static(p, *polar, *solver, {corotational, 5, 1e-10, 200});
  ASSERT_TRUE(s.converged);
  // First bending mode omega ~ 7.2 rad/s; alpha = 15/s damps it critically, so after 12 s the
  // transient has decayed by ~e^-80; what remains is the solver round-off.
  DynamicOptions o{corotational, 0.02, 600, 15.0, 0.0};
  bool supports_still = true;
  const SimulationResult d = solve_dynamic(p, *polar, *solver, o, [&](const StepState& st) {
    for (int i = 0; i < p.num_dofs(); ++i)
      if (p.dirichlet.fixed[i] && st.displacement[i] != 0) supports_still = false;
  });
  EXPECT_TRUE(supports_still);
  EXPECT_LT((d.displacement - s.displacement).norm(), 1e-6 * s.displacement.norm());
  EXPECT_LT(d.residual, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Formulations, DampedSettling, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "corotational" : "linear"; });

TEST(ImplicitEuler, AssemblingIntoTheSystemMatrixIsTheScaledCopyAndKeepsKtildeOnRequest) {
  // The linearly implicit step has the assembly write (dt beta + dt^2) Ktilde straight into A;
  // with keep_stiffness it assembles Ktilde into problem.stiffness and scales a copy, as before.
  // The two differ by round-off in A (the scale enters V lambda and V mu, not the sums; the mass
  // is added at a block's first store, not after its sum), so the trajectories agree to
  // round-off amplified by cond(A) (~1e4 here): 1e-10.
  const Cantilever bar;
  DynamicOptions o{true, 0.01, 12, 1.0, 0.002};
  FeProblem fused = bar.build(1, 3.0), kept = bar.build(1, 3.0);
  auto polar = make_rotation_extractor(RotationMethod::Polar, fused.mesh);
  auto solver = make_cholmod_solver();
  const SimulationResult a = solve_dynamic(fused, *polar, *solver, o);
  o.keep_stiffness = true;
  Eigen::VectorXd before = Eigen::VectorXd::Zero(kept.num_dofs());
  int checked = 0;
  const SimulationResult b = solve_dynamic(kept, *polar, *solver, o, [&](const StepState& st) {
    // problem.stiffness is this step's Ktilde: the one assembled from its rotations at the
    // displacement the step started from.
    BrcMatrix k = kept.stiffness;
    Eigen::VectorXd force;
    assemble_corotated(kept.elements, kept.mesh, kept.assembly, st.rotations, before, k, force);
    EXPECT_TRUE(k.values == kept.stiffness.values) << "step " << st.step;
    before = st.displacement;
    ++checked;
  });
  EXPECT_EQ(checked, 12);
  ASSERT_GT(a.displacement.norm(), 0);
  EXPECT_LT((a.displacement - b.displacement).norm(), 1e-10 * a.displacement.norm());
}

/// Solves exactly (CHOLMOD) and, at every solve, measures the start it is handed against the
/// linear extrapolation of its own last two solutions, both in the energy norm of the error.
class StartJudge : public LinearSolver {
 public:
  std::string name() const override { return "judge"; }
  void set_matrix(const BrcMatrix& a) override {
    dense_ = to_eigen(a);
    inner_->set_matrix(a);
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    const Eigen::VectorXd start = x;
    const SolveStats stats = inner_->solve(b, x);
    auto energy = [&](const Eigen::VectorXd& e) { return std::sqrt(e.dot(dense_ * e)); };
    if (last_.size() == 0) last_ = previous_ = Eigen::VectorXd::Zero(x.size());
    given.push_back(energy(start - x));
    extrapolated.push_back(energy(2 * last_ - previous_ - x));
    previous_ = last_;
    last_ = x;
    return stats;
  }
  std::vector<double> given, extrapolated;

 private:
  std::unique_ptr<LinearSolver> inner_ = make_cholmod_solver();
  Eigen::MatrixXd dense_;
  Eigen::VectorXd last_, previous_;
};

TEST(ImplicitEuler, AProjectedStartIsNearerTheSolutionThanTheExtrapolation) {
  // start_history 4: each solve starts from the projection on the last four velocities
  // (linalg/projected_start.hpp), which span the extrapolation 2 v_n - v_{n-1}: its energy-norm
  // error is at most the extrapolation's (up to round-off, 1e-8 relative), and at 0 the
  // extrapolation itself is handed over (the same error).
  const Cantilever bar;
  for (const int history : {4, 0}) {
    DynamicOptions o{true, 0.01, 12, 1.0, 0.0};
    o.start_history = history;
    FeProblem p = bar.build(1, 3.0);
    auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
    StartJudge judge;
    solve_dynamic(p, *polar, judge, o);
    ASSERT_EQ(judge.given.size(), 12u);
    double given = 0, extrapolated = 0;
    for (std::size_t n = 0; n < judge.given.size(); ++n) {
      EXPECT_LE(judge.given[n], judge.extrapolated[n] * (1 + 1e-8))
          << "history " << history << ", step " << n + 1;
      if (history == 0) {
        EXPECT_NEAR(judge.given[n], judge.extrapolated[n], 1e-8 * judge.extrapolated[n]);
      }
      given += judge.given[n];
      extrapolated += judge.extrapolated[n];
    }
    // the bar falls and swings: its starts are strictly nearer, not merely as near
    if (history > 0) {
      EXPECT_LT(given, 0.9 * extrapolated);
    }
  }
}

/// Counts the matrices a solver is handed.
class MatrixCounter : public LinearSolver {
 public:
  explicit MatrixCounter(std::unique_ptr<LinearSolver> inner) : inner_(std::move(inner)) {}
  std::string name() const override { return inner_->name(); }
  void set_matrix(const BrcMatrix& a) override {
    ++matrices;
    inner_->set_matrix(a);
  }
  void take_matrix(BrcMatrix& a) override {
    ++matrices;
    inner_->take_matrix(a);
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    return inner_->solve(b, x);
  }
  int matrices = 0;

 private:
  std::unique_ptr<LinearSolver> inner_;
};

TEST(ImplicitEuler, SmallStrainFormsItsMatrixOnlyWhenTheSupportsChange) {
  // Small strain, K is constant: the step hands A to the solver at the first step and when the
  // supported DOFs change, and takes f_int = K u and the supports' lift from one product with K.
  // The oracle is the same linearly implicit Euler written densely: A = (1 + dt alpha) M +
  // (dt beta + dt^2) K, b = M v + dt (f - K u), the prescribed velocities eliminated from the free
  // rows, solved by LU. The root rises at every step and, from step 5, the tip face is held too,
  // moving down: the lift is not zero, and the supports change once. CHOLMOD against LU on
  // cond(A) ~ 1e4: round-off well under 1e-9.
  const Cantilever bar;
  const double dt = 0.01, alpha = 1.0, beta = 0.002;
  const int steps = 12, tip_from = 5;
  FeProblem p = bar.build(1), oracle = bar.build(1);
  const std::vector<int> root =
      vertices_in_box(p.mesh.rest, {Vec3::Zero(), Vec3(0, bar.height, bar.height)});
  const std::vector<int> tip = vertices_in_box(
      p.mesh.rest, {Vec3(bar.length, 0, 0), Vec3(bar.length, bar.height, bar.height)});
  ASSERT_FALSE(root.empty());
  ASSERT_FALSE(tip.empty());
  const auto supports = [&](int step, FeProblem& f) {
    for (int v : root) f.dirichlet.fix_vertex(v, Vec3(0, 0, 1e-3 * step));
    if (step >= tip_from)
      for (int v : tip) f.dirichlet.fix_vertex(v, Vec3(0, 0, -2e-3 * (step - tip_from + 1)));
  };

  const int n = oracle.num_dofs();
  BrcMatrix k_blocks = oracle.stiffness;
  Eigen::VectorXd unused;
  assemble_corotated(oracle.elements, oracle.mesh, oracle.assembly,
                     std::vector<Mat3>(oracle.mesh.tets.size(), Mat3::Identity()),
                     Eigen::VectorXd::Zero(n), k_blocks, unused);
  BrcToEigen to_eigen(k_blocks);
  to_eigen.update(k_blocks);
  const Eigen::MatrixXd k = to_eigen.matrix().toDense();
  const Eigen::MatrixXd a =
      Eigen::MatrixXd(oracle.mass.asDiagonal()) * (1 + dt * alpha) + (dt * beta + dt * dt) * k;
  std::vector<Eigen::VectorXd> expected;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  for (int step = 1; step <= steps; ++step) {
    supports(step, oracle);
    const std::vector<char>& fixed = oracle.dirichlet.fixed;
    std::vector<int> free_dofs;
    Eigen::VectorXd next = Eigen::VectorXd::Zero(n);
    for (int d = 0; d < n; ++d)
      if (fixed[d])
        next[d] = (oracle.dirichlet.value[d] - u[d]) / dt;
      else
        free_dofs.push_back(d);
    const Eigen::VectorXd rhs =
        oracle.mass.cwiseProduct(v) + dt * (oracle.external_force - k * u) - a * next;
    const int m = static_cast<int>(free_dofs.size());
    Eigen::MatrixXd a_free(m, m);
    Eigen::VectorXd b_free(m);
    for (int i = 0; i < m; ++i) {
      b_free[i] = rhs[free_dofs[i]];
      for (int j = 0; j < m; ++j) a_free(i, j) = a(free_dofs[i], free_dofs[j]);
    }
    const Eigen::VectorXd v_free = a_free.partialPivLu().solve(b_free);
    for (int i = 0; i < m; ++i) next[free_dofs[i]] = v_free[i];
    v = next;
    u += dt * v;
    expected.push_back(u);
  }

  ASSERT_GT(expected.back().norm(), 0);  // the comparison below is not of zeros
  MatrixCounter solver(make_cholmod_solver());
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  DynamicOptions o{false, dt, steps, alpha, beta};
  o.before_step = supports;
  int checked = 0;
  solve_dynamic(p, *polar, solver, o, [&](const StepState& st) {
    const Eigen::VectorXd& want = expected[st.step - 1];
    EXPECT_LT((st.displacement - want).norm(), 1e-9 * want.norm()) << "step " << st.step;
    ++checked;
  });
  EXPECT_EQ(checked, steps);
  EXPECT_EQ(solver.matrices, 2);  // the first step's A, and the one with the tip held
}

TEST(ImplicitEuler, FreeFallUnderGravityIsExactForRigidTranslation) {
  // No supports, uniform gravity: the body translates rigidly; implicit Euler's discrete
  // trajectory is u_n = -g dt^2 n(n+1)/2 exactly (no strain, so no elastic force).
  const Cantilever bar;
  FeProblem p = bar.build(1);
  p.dirichlet = DirichletConditions::none(p.num_dofs());
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  auto solver = make_cholmod_solver();
  const int n = 20;
  const double dt = 0.01;
  const SimulationResult d = solve_dynamic(p, *polar, *solver, {true, dt, n, 0, 0});
  const double expected = -bar.gravity * dt * dt * n * (n + 1) / 2;
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    ASSERT_NEAR(d.displacement[3 * v + 2], expected, 1e-9 * std::abs(expected));
}

}  // namespace
}  // namespace corofem
