// CalculiX as the outside oracle: the linear C3D4 solve of the same deck equals corofem's to
// CalculiX's printed digits (7 significant), and under NLGEOM the corotated models land near
// St. Venant-Kirchhoff on a bar that bends through large rotations at small strain, where small
// strain does not. Skips without ccx.
#include <gtest/gtest.h>

#include <iostream>

#include "cantilever_fixture.hpp"
#include "integrate/static_solver.hpp"
#include "linalg/linear_solver.hpp"
#include "report/calculix_oracle.hpp"
#include "rotation/rotation_extractor.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

Eigen::VectorXd corofem_static(FeProblem& p, const std::string& method, bool corotational) {
  auto rotation = make_rotation_extractor(rotation_method_named(method), p.mesh);
  auto solver = make_cholmod_solver();
  const SimulationResult r =
      solve_static(p, *rotation, *solver, {corotational, 20, 1e-10, 30, true});
  EXPECT_TRUE(r.converged) << r.message;
  return r.displacement;
}

TEST(Calculix, LinearSolveEqualsCalculixToItsPrintedDigits) {
  if (!calculix_available()) GTEST_SKIP() << "ccx (calculix-ccx) not on PATH; ci/setup installs it";
  test::TempDir dir;
  FeProblem p = test::Cantilever{}.build(1);
  const Eigen::VectorXd ours = corofem_static(p, "polar", false);
  const Eigen::VectorXd theirs = run_calculix(p, false, dir.path(), "linear");
  // ccx prints 7 significant digits: each value within 5e-7 of itself, so 1e-6 of the largest.
  const double largest = theirs.cwiseAbs().maxCoeff();
  EXPECT_LT((ours - theirs).cwiseAbs().maxCoeff(), 1e-6 * largest) << "largest " << largest;
}

TEST(Calculix, RelativeWorkingFolderGivesTheSameAnswer) {
  // ci/report writes into out/report, a relative path: the job must run there as it does in an
  // absolute folder (the command changes into the folder before writing its log, which once made
  // every job of the main job's model-accuracy section fail, exit 2 and an empty log).
  if (!calculix_available()) GTEST_SKIP() << "ccx (calculix-ccx) not on PATH; ci/setup installs it";
  test::TempDir dir;
  FeProblem p = test::Cantilever{}.build(1);
  const Eigen::VectorXd absolute = run_calculix(p, false, dir / "absolute", "linear");
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  Eigen::VectorXd relative;
  try {
    relative = run_calculix(p, false, "out/report/calculix", "linear");
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
  std::filesystem::current_path(before);
  ASSERT_EQ(relative.size(), absolute.size());
  EXPECT_EQ(relative, absolute);  // the same deck, the same printed digits
  EXPECT_TRUE(std::filesystem::exists(dir / "out/report/calculix/linear.dat"));
}

TEST(Calculix, NonlinearBendingAgainstNlgeom) {
  if (!calculix_available()) GTEST_SKIP() << "ccx (calculix-ccx) not on PATH; ci/setup installs it";
  test::TempDir dir;
  test::Cantilever soft;
  soft.young = 1e6;  // droops about half its length: rotations near 1 rad, strains about 1%
  FeProblem p = soft.build(1);
  const Eigen::VectorXd theirs = run_calculix(p, true, dir.path(), "nlgeom");
  const auto error = [&](const std::string& method) {
    return (corofem_static(p, method, true) - theirs).norm() / theirs.norm();
  };
  const double polar = error("polar"), energy = error("energy-exact");
  const double linear = (corofem_static(p, "polar", false) - theirs).norm() / theirs.norm();
  std::cout << "relative displacement error against CalculiX NLGEOM: polar " << polar
            << ", energy-exact " << energy << ", linear " << linear << "\n";
  // Same mesh, same loads: what remains is the model. Corotated linear and St. Venant-Kirchhoff
  // agree to first order in the strain (about 1% here): a few percent; small strain misses the
  // rotation (measured: polar 2.1%, energy-exact 1.9%, linear 19%).
  EXPECT_LT(polar, 0.05);
  EXPECT_LT(energy, 0.05);
  EXPECT_GT(linear, 0.1);
}

}  // namespace
}  // namespace corofem
