// The solver registry (scene/solver_kind.hpp): the built-ins by name in their fixed places, a
// solver of one's own registered in one call with a setting of its own that scenes give, check
// and record, and its answer against CHOLMOD's.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "linalg/preconditioned_cg.hpp"
#include "scene/scene_simulation.hpp"
#include "scene/solver_kind.hpp"

namespace corofem {
namespace {

using json = nlohmann::json;

TEST(SolverRegistry, BuiltInsByNameInTheirPlaces) {
  const std::vector<std::string> expected = {"cholmod",    "multigrid",  "mgpcg",
                                             "jacobi-pcg", "petsc-gamg", "hypre-boomeramg",
                                             "petsc-mg",   "auto"};
  ASSERT_GE(solver_names().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(solver_names()[k], expected[k]);
    EXPECT_EQ(solver_named(expected[k]).id(), static_cast<int>(k));
  }
  EXPECT_EQ(SolverKind::Mgpcg.name(), "mgpcg");
  EXPECT_FALSE(find_solver("gauss").has_value());
  try {
    solver_named("gauss");
    ADD_FAILURE() << "an unknown solver was found";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("registered: cholmod, multigrid"), std::string::npos);
  }
  // What the rest of corofem reads of a solver is its traits'.
  EXPECT_TRUE(SolverKind::PetscMg.traits().multigrid);
  EXPECT_TRUE(SolverKind::PetscMg.traits().petsc.has_value());
  EXPECT_TRUE(SolverKind::Auto.traits().builds_hierarchy);
  EXPECT_FALSE(SolverKind::JacobiPcg.traits().builds_hierarchy);
  EXPECT_TRUE(SolverKind::Cholmod.traits().factorizes);
}

json bar_scene(const std::string& solver) {
  return {
      {"mesh", {{"box", {1, 0.2, 0.2}}, {"cells", {8, 2, 2}}}},
      {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
      {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 0.2, 0.2}}}}}},
      {"gravity", {0, 0, -9.81}},
      {"analysis", {{"type", "dynamic"}, {"solver", solver}, {"steps", 3}, {"tolerance", 1e-10}}}};
}

TEST(SolverRegistry, ASolverOfOnesOwnWithASettingOfItsOwn) {
  // Jacobi-PCG with a cap of its own: "capped-pcg", its setting analysis.capped_iterations.
  const SolverKind capped = register_solver(
      {.name = "capped-pcg",
       .make =
           [](const SolverRequest& r) {
             return make_jacobi_pcg_solver(
                 r.analysis.tolerance,
                 static_cast<int>(r.analysis.solver_parameters.integer("capped_iterations")));
           },
       .parameters = {{.key = "capped_iterations",
                       .kind = ParameterSpec::Kind::Integer,
                       .fallback = 1000LL,
                       .min = 1,
                       .max = 100000}},
       .bytes_per_tet = 1.3e3});
  EXPECT_THROW(register_solver({.name = "capped-pcg", .make = SolverKind::Cholmod.traits().make}),
               std::invalid_argument);
  json scene = bar_scene("capped-pcg");
  scene["analysis"]["capped_iterations"] = 400;
  const Scene parsed = parse_scene(scene, ".", "bar.json");
  EXPECT_EQ(parsed.analysis.solver, capped);
  EXPECT_EQ(parsed.analysis.solver_parameters.integer("capped_iterations"), 400);
  // Its answer: CHOLMOD's, to the tolerance's order.
  SceneSimulation mine(parsed), oracle(parse_scene(bar_scene("cholmod"), ".", "bar.json"));
  const SimulationResult a = mine.run(), b = oracle.run();
  EXPECT_LT((a.displacement - b.displacement).norm(), 1e-7 * b.displacement.norm());
  // Out of its declared range: refused, naming the key.
  scene["analysis"]["capped_iterations"] = 0;
  try {
    parse_scene(scene, ".", "bar.json");
    ADD_FAILURE() << "capped_iterations 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("analysis.capped_iterations must be in [1, 100000]"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace corofem
