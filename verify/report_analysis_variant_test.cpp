// The report's typed scene variants (report/analysis_variant.hpp): what they write is what the
// scene parser reads back, and a change to a solver that is not multigrid drops the multigrid
// keys, which that solver would warn about.
#include <gtest/gtest.h>

#include <set>

#include "report/analysis_variant.hpp"
#include "scene/scene.hpp"

namespace corofem {
namespace {

nlohmann::json mgpcg_scene() {
  return {{"mesh", {{"box", {1, 0.5, 0.5}}, {"cells", {4, 2, 2}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {1e-6, 0.5, 0.5}}}}}},
          {"analysis",
           {{"type", "dynamic"},
            {"solver", "mgpcg"},
            {"levels", 2},
            {"smoothing", 2},
            {"tolerance", 1e-4}}}};
}

TEST(AnalysisVariant, WritesWhatTheSceneParserReadsBack) {
  const AnalysisVariant variant{.solver = SolverKind::Multigrid,
                                .rotation = RotationMethod::PolarSmoothed,
                                .galerkin = GalerkinMethod::Naive,
                                .hierarchy = HierarchyKind::Lattice,
                                .tolerance = 1e-6,
                                .vcycles = 3};
  const Scene s = parse_scene(with_analysis(mgpcg_scene(), variant), "/base", "variant.json");
  EXPECT_EQ(s.analysis.solver, SolverKind::Multigrid);
  EXPECT_EQ(s.analysis.rotation, RotationMethod::PolarSmoothed);
  EXPECT_EQ(s.analysis.multigrid.galerkin, GalerkinMethod::Naive);
  EXPECT_EQ(s.analysis.multigrid.hierarchy.kind, HierarchyKind::Lattice);
  EXPECT_EQ(s.analysis.tolerance, 1e-6);
  EXPECT_EQ(s.analysis.multigrid.vcycles, 3);
  EXPECT_EQ(s.analysis.multigrid.hierarchy.levels, 2);  // the scene's, untouched
  EXPECT_EQ(s.analysis.multigrid.pre_smoothing, 2);     // likewise
  // The label names the set fields in key order, as the speed-accuracy points show them.
  EXPECT_EQ(label_of(variant),
            "galerkin=naive hierarchy=lattice rotation=polar-smoothed solver=multigrid "
            "tolerance=1e-06 vcycles=3");
}

TEST(AnalysisVariant, AnotherSolverDropsTheMultigridKeys) {
  // Every multigrid key spelled out here, not read from the list the code erases by: a key
  // dropped from that list must fail this gate.
  const char* keys[] = {"levels",
                        "vcycles",
                        "smoothing",
                        "galerkin",
                        "hierarchy",
                        "smoother",
                        "coarsest_vertices",
                        "coarsest_max_vertices",
                        "coarsening",
                        "chebyshev_degree",
                        "cycle",
                        "coarsest_refactor",
                        "galerkin_refresh"};
  // And the spelled list is the production one, key for key: a key added there is spelled here.
  const std::vector<std::string> production = multigrid_analysis_keys();
  EXPECT_EQ(std::set<std::string>(std::begin(keys), std::end(keys)),
            std::set<std::string>(production.begin(), production.end()));
  nlohmann::json scene = mgpcg_scene();
  scene["analysis"].update({{"vcycles", 30},
                            {"galerkin", "stream"},
                            {"hierarchy", "lattice"},
                            {"smoother", "multicolour"},
                            {"coarsest_vertices", 300},
                            {"coarsest_max_vertices", 500},
                            {"coarsening", 3.5},
                            {"chebyshev_degree", 3},
                            {"cycle", "W"},
                            {"coarsest_refactor", 0.1},
                            {"galerkin_refresh", 0.05}});
  for (const char* key : keys) ASSERT_TRUE(scene["analysis"].contains(key)) << key;
  const nlohmann::json cholmod = with_analysis(scene, {.solver = SolverKind::Cholmod});
  for (const char* key : keys) EXPECT_FALSE(cholmod["analysis"].contains(key)) << key;
  EXPECT_EQ(cholmod["analysis"]["tolerance"], 1e-4);
  // A change that leaves the solver keeps them.
  const nlohmann::json polar = with_analysis(mgpcg_scene(), {.rotation = RotationMethod::Polar});
  EXPECT_EQ(polar["analysis"]["levels"], 2);
  EXPECT_EQ(polar["analysis"]["solver"], "mgpcg");
}

}  // namespace
}  // namespace corofem
