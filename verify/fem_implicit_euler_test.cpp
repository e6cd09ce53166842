// Implicit Euler: a damped cantilever comes to rest at the static solution of the same
// formulation (the static solver is the oracle); supports never move.
#include <gtest/gtest.h>

#include "cantilever_fixture.hpp"
#include "fem/corotated_assembly.hpp"
#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "rotation/rotation_extractor.hpp"

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
