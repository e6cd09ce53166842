// Static cantilever: linear convergence under refinement against beam theory; corotated equals
// linear for a tiny load; under a large load the corotated bar shortens and drops less.
#include <gtest/gtest.h>

#include <cmath>

#include "cantilever_fixture.hpp"
#include "integrate/static_solver.hpp"
#include "rotation/rotation_extractor.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::Cantilever;

// Residual tolerance 1e-9: two decades above the round-off floor of the element forces,
// eps |K_e| h_e / |f| ~ 1e-11 at standard gravity on these meshes.
Vec3 solve_tip(const Cantilever& bar, int k, bool corotational, double gravity_scale,
               int load_steps = 1, SimulationResult* out = nullptr, double tolerance = 1e-9) {
  FeProblem p = bar.build(k, gravity_scale);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  auto solver = make_cholmod_solver();
  SimulationResult r = solve_static(p, *polar, *solver, {corotational, load_steps, tolerance, 200});
  EXPECT_TRUE(r.converged) << r.message;
  if (out) *out = r;
  return Cantilever::tip_displacement(p, r.displacement);
}

TEST(Cantilever, LinearDeflectionConvergesUnderRefinement) {
  const Cantilever bar;
  // k = 1 (one cell across) is deep in shear locking and shows no rate; start at 2.
  const std::vector<int> ks = {2, 4, 8};
  std::vector<double> w;
  for (int k : ks) w.push_back(-solve_tip(bar, k, false, 1.0).z());
  const double beam = bar.beam_theory_deflection();
  const double rate = std::log2((w[1] - w[0]) / (w[2] - w[1]));
  std::cout << "[ cantilever ] tip deflection k=" << ks[0] << "," << ks[1] << "," << ks[2] << ": "
            << w[0] << ", " << w[1] << ", " << w[2] << "; Timoshenko " << beam << "; observed rate "
            << rate << "\n";
  // Stiff linear tets approach from below, monotonically; the observed rate of the successive
  // differences sits between O(h) (pre-asymptotic shear locking) and O(h^2) (asymptotic).
  EXPECT_LT(w[0], w[1]);
  EXPECT_LT(w[1], w[2]);
  EXPECT_LT(w[2], 1.02 * beam);
  EXPECT_GT(rate, 0.7);
  EXPECT_LT(rate, 2.5);
}

TEST(Cantilever, CorotatedEqualsLinearForTinyLoad) {
  const Cantilever bar;
  // Load 1e-6 of the standard: rotations ~1e-7 rad, so corotated differs from linear at
  // second order, ~1e-7 relative; 1e-6 leaves a margin of 10. The residual floor relative to so
  // small a load is eps |K_e| h_e / |f| ~ 1e-5, hence the residual tolerance 1e-4 here; the
  // displacement comparison below is the real gate.
  const Vec3 lin = solve_tip(bar, 2, false, 1e-6);
  const Vec3 cor = solve_tip(bar, 2, true, 1e-6, 1, nullptr, 1e-4);
  EXPECT_LT((cor - lin).norm(), 1e-6 * lin.norm());
}

TEST(Cantilever, LargeLoadCorotatedShortensAndDropsLess) {
  const Cantilever bar;
  // Four times the standard gravity: linear tip drop ~0.6 L, far in the large-rotation range.
  SimulationResult r;
  const Vec3 lin = solve_tip(bar, 2, false, 4.0);
  const Vec3 cor = solve_tip(bar, 2, true, 4.0, 10, &r);
  std::cout << "[ cantilever ] 4g tip: linear " << lin.transpose() << ", corotated "
            << cor.transpose() << " (" << r.iterations << " iterations, residual " << r.residual
            << ")\n";
  EXPECT_LT(cor.x(), -0.05 * bar.length);           // moves toward the root
  EXPECT_LT(std::abs(lin.x()), 0.01 * bar.length);  // linear: no shortening to first order
  EXPECT_LT(-cor.z(), -lin.z());                    // drops less
  EXPECT_GT(-cor.z(), 0.2 * bar.length);
  EXPECT_LT(r.residual, 1e-9);
}

TEST(StaticSolver, NonConvergenceIsReportedNotThrown) {
  const Cantilever bar;
  FeProblem p = bar.build(1, 4.0);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  auto solver = make_cholmod_solver();
  const SimulationResult r = solve_static(p, *polar, *solver, {true, 1, 1e-12, 2});
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("did not reach tolerance"), std::string::npos);
}

}  // namespace
}  // namespace corofem
