// The smoother registry: the built-ins by name, and a smoother registered from outside lib/
// (bench/own_method's damped l1 block Jacobi) reaching the scene parser, the V-cycle, the record
// and the roofline without a change elsewhere; its MG-PCG answer checked against CHOLMOD.
// Registration changes the process for good, so it runs in a child process (a death test's
// fork).
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "io/solver_record.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "own_method.hpp"
#include "report/step_roofline.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {
namespace {

using nlohmann::json;

TEST(SmootherRegistry, BuiltInsByName) {
  const std::vector<std::string> expected = {"sequential", "multicolour", "domains", "hybrid",
                                             "chebyshev"};
  ASSERT_GE(smoother_names().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(smoother_names()[k], expected[k]);
  EXPECT_EQ(make_smoother("domains")->describe().text("ordering"), "domains");
  Parameters degree_4;
  degree_4.set("chebyshev_degree", 4LL);
  EXPECT_EQ(make_smoother("chebyshev", degree_4)->describe().integer("degree"), 4);
  EXPECT_EQ(make_smoother("chebyshev")->describe().integer("degree"), 2);  // its default
  try {
    make_smoother("jacobi", {});
    ADD_FAILURE() << "an unknown smoother was made";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("hybrid"), std::string::npos) << e.what();
  }
}

json cube_scene() {
  return {{"mesh", {{"box", {1, 1, 1}}, {"cells", {6, 6, 6}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 1, 1}}}}}},
          {"gravity", {0, 0, -9.81}},
          {"analysis",
           {{"type", "static"},
            {"formulation", "linear"},
            {"solver", "mgpcg"},
            {"levels", 2},
            {"tolerance", 1e-11}}}};
}

void register_and_use_a_smoother_of_ones_own() {
  own::register_damped_l1_jacobi();
  EXPECT_THROW(
      register_smoother({.name = own::kDampedL1Jacobi, .make = find_smoother("hybrid")->make}),
      std::invalid_argument);

  // The example's own checks: MG-PCG with it against CHOLMOD (and its rotation method against
  // the exact minimizer).
  own::register_energy_mueller();
  EXPECT_EQ(own::check_against_oracles(), 0);

  json scene = cube_scene();
  scene["analysis"]["smoother"] = own::kDampedL1Jacobi;
  SceneSimulation mine(parse_scene(scene, ".", "cube.json"));
  mine.run();

  const auto& solver = dynamic_cast<const MultigridSolver&>(mine.solver());
  EXPECT_EQ(to_json(solver.params())["smoother"]["kind"], "damped-l1-jacobi");
  EXPECT_EQ(to_json(solver.params())["smoother"]["damping"], 0.8);
  // The roofline counts its sweeps: a V-cycle on two levels reads the fine matrix once a
  // smoothing and once for the residual, an iteration once more for CG's product.
  const FeProblem& problem = mine.problem();
  const double v = problem.mesh.num_vertices();
  const double blocks = static_cast<double>(problem.stiffness.col_index.size());
  const double fine_matrix = 76 * blocks + 4 * (v + 1);
  const double per_iteration = step_traffic(problem, solver, 0, 6.0).at("solve").bytes -
                               step_traffic(problem, solver, 0, 5.0).at("solve").bytes;
  const double n = 3 * v, cg_vectors = 15 * 8 * n;
  const MultigridHierarchy& h = solver.hierarchy();
  ASSERT_EQ(h.num_levels(), 2);
  const double coarsest =
      16 * solver.coarsest_factor_nonzeros() + 32 * 3.0 * h.matrix(1).block_rows;
  EXPECT_GE(per_iteration, 4 * fine_matrix + cg_vectors + coarsest);
  // Besides: its two sweeps' inverse diagonal and vectors, the transfers (under 200 B a DOF).
  EXPECT_LE(per_iteration,
            4 * fine_matrix + cg_vectors + coarsest + 2 * (72 * v + 48 * n) + 200 * n);
  std::exit(::testing::Test::HasFailure() ? 1 : 0);
}

TEST(SmootherRegistryDeathTest, ASmootherOfOnesOwnIsParsedRunAndCounted) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(register_and_use_a_smoother_of_ones_own(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace corofem
