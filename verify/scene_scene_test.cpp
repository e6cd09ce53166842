// Scene parsing: defaults, path resolution, and an error naming the key for every kind of bad
// value.
#include "scene/scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/errors.hpp"
#include "scene/scene_paths.hpp"
#include "scene/solver_factory.hpp"

namespace corofem {
namespace {

nlohmann::json minimal() {
  return nlohmann::json::parse(R"({
    "mesh": {"box": [1, 0.1, 0.1], "cells": [4, 1, 1]},
    "material": {"young": 1e6, "poisson": 0.3},
    "fixed": [{"box": [[0, 0, 0], [0, 0.1, 0.1]]}]
  })");
}

TEST(Scene, MinimalSceneGetsDefaults) {
  const Scene s = parse_scene(minimal(), "/base", "s.json");
  EXPECT_EQ(s.mesh.kind, MeshSpec::Kind::Box);
  EXPECT_EQ(s.analysis.type, AnalysisType::Static);
  EXPECT_EQ(s.analysis.formulation, Formulation::Corotational);
  EXPECT_EQ(s.analysis.rotation, RotationMethod::Polar);
  EXPECT_EQ(s.fixed.size(), 1u);
}

TEST(Scene, AStaticRunFindsIterativeRotationsBelowItsTolerance) {
  // The rotations' own error must not set the floor of the static residual: 1e-5 x tolerance,
  // unless the scene says; a dynamic run keeps the extractors' defaults.
  auto j = minimal();
  j["analysis"] = {{"rotation", "energy-newton"}, {"tolerance", 1e-6}};
  // The method's own settings only: energy-newton's, mueller2016's under its own name.
  Parameters p = parse_scene(j, "/base", "s.json").analysis.rotation_params;
  EXPECT_DOUBLE_EQ(p.number("newton_tolerance"), 1e-11);
  EXPECT_FALSE(p.has("mueller_tolerance"));
  j["analysis"]["rotation"] = "mueller2016";
  EXPECT_DOUBLE_EQ(
      parse_scene(j, "/base", "s.json").analysis.rotation_params.number("mueller_tolerance"),
      1e-11);
  j["analysis"]["rotation"] = "energy-newton";
  j["analysis"]["tolerance"] = 1e-12;  // never below what the scene allows any tolerance
  EXPECT_DOUBLE_EQ(
      parse_scene(j, "/base", "s.json").analysis.rotation_params.number("newton_tolerance"), 1e-15);
  // A setting the scene gives is the scene's; another method's is checked and left unused.
  j["analysis"]["rotation_params"] = {{"newton_tolerance", 1e-7}, {"mueller_iterations", 5}};
  p = parse_scene(j, "/base", "s.json").analysis.rotation_params;
  EXPECT_DOUBLE_EQ(p.number("newton_tolerance"), 1e-7);
  EXPECT_FALSE(p.has("mueller_iterations"));
  j["analysis"]["rotation_params"] = {{"mueller_iterations", 0}};
  EXPECT_THROW(parse_scene(j, "/base", "s.json"), InputError);  // out of mueller2016's range
  j["analysis"]["rotation_params"] = {{"newton_speed", 1}};
  EXPECT_THROW(parse_scene(j, "/base", "s.json"), InputError);  // no method declares it
  j["analysis"] = {{"type", "dynamic"}, {"tolerance", 1e-6}, {"rotation", "energy-newton"}};
  j["material"]["density"] = 1000;
  p = parse_scene(j, "/base", "s.json").analysis.rotation_params;
  EXPECT_EQ(p.number("newton_tolerance"), 1e-9);  // its declared default
}

TEST(Scene, SmootherNamesAnOrderingOrChebyshev) {
  auto j = minimal();
  j["analysis"] = {{"solver", "mgpcg"}, {"smoother", "domains"}};
  Scene s = parse_scene(j, "/base", "s.json");
  EXPECT_EQ(s.analysis.multigrid.smoother, "domains");
  j["analysis"] = {{"solver", "mgpcg"}, {"smoother", "chebyshev"}, {"chebyshev_degree", 3}};
  s = parse_scene(j, "/base", "s.json");
  EXPECT_EQ(s.analysis.multigrid.smoother, "chebyshev");
  EXPECT_EQ(s.analysis.multigrid.smoother_parameters.integer("chebyshev_degree"), 3);
  EXPECT_EQ(multigrid_params(s.analysis).smoother_parameters.integer("chebyshev_degree"), 3);
  j["analysis"]["smoother"] = "jacobi";
  EXPECT_THROW(parse_scene(j, "/base", "s.json"), InputError);
  j["analysis"]["smoother"] = "chebyshev";
  j["analysis"]["chebyshev_degree"] = 0;
  EXPECT_THROW(parse_scene(j, "/base", "s.json"), InputError);
}

TEST(Scene, CycleIsVOrW) {
  auto j = minimal();
  j["analysis"] = {{"solver", "mgpcg"}};
  EXPECT_EQ(parse_scene(j, "/base", "s.json").analysis.multigrid.cycle, CycleShape::V);
  j["analysis"]["cycle"] = "W";
  const Scene s = parse_scene(j, "/base", "s.json");
  EXPECT_EQ(s.analysis.multigrid.cycle, CycleShape::W);
  EXPECT_EQ(multigrid_params(s.analysis).cycle, CycleShape::W);
  j["analysis"]["cycle"] = "F";
  try {
    parse_scene(j, "/base", "s.json");
    ADD_FAILURE() << "cycle F accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos) << e.what();
  }
}

TEST(Scene, CoarseningIsZeroOrARatioOfAtLeastTwo) {
  auto j = minimal();
  j["analysis"] = {{"solver", "mgpcg"}};
  EXPECT_EQ(parse_scene(j, "/base", "s.json").analysis.multigrid.hierarchy.coarsening, 0);
  j["analysis"]["coarsening"] = 3.5;
  const Scene s = parse_scene(j, "/base", "s.json");
  EXPECT_EQ(multigrid_params(s.analysis).hierarchy.coarsening, 3.5);
  for (const double bad : {1.2, -1.0, 100.0}) {
    j["analysis"]["coarsening"] = bad;
    try {
      parse_scene(j, "/base", "s.json");
      ADD_FAILURE() << "coarsening " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("coarsening"), std::string::npos) << e.what();
    }
  }
}

TEST(Scene, RelativePathsResolveAgainstSceneFolder) {
  auto j = minimal();
  j["mesh"] = {{"file", "meshes/a.msh"}};
  j["output"] = {{"vtu", "out/r.vtu"}};
  const Scene s = parse_scene(j, "/base/dir", "s.json");
  EXPECT_EQ(s.mesh.path, std::filesystem::path("/base/dir/meshes/a.msh"));
  EXPECT_EQ(*s.output.vtu, std::filesystem::path("/base/dir/out/r.vtu"));
}

TEST(Scene, MovedSceneNamesTheSameFiles) {
  // corofem tune writes its answer into another folder: its relative paths follow.
  auto j = minimal();
  j["mesh"] = {{"surface", "models/a.stl"},
               {"size", 0.1},
               {"levels", {{{"surface", "models/a_L1.stl"}, {"size", 0.2}}}}};
  j["output"] = {{"vtu", "r.vtu"}};
  const std::filesystem::path from = "/data/scenes", to = "/data/out/tune";
  const nlohmann::json moved = with_paths_moved(j, from, to);
  const Scene original = parse_scene(j, from, "s.json");
  const Scene there = parse_scene(moved, to, "s.json");
  EXPECT_EQ(there.mesh.path.lexically_normal(), original.mesh.path.lexically_normal());
  EXPECT_EQ(there.mesh.levels.at(0).path.lexically_normal(),
            original.mesh.levels.at(0).path.lexically_normal());
  EXPECT_EQ(there.output.vtu->lexically_normal(), original.output.vtu->lexically_normal());
  EXPECT_EQ(moved["mesh"]["surface"], "../../scenes/models/a.stl");
}

TEST(Scene, SimplifyIsASurfaceKey) {
  auto j = minimal();
  j["mesh"] = {{"surface", "a.stl"}, {"size", 0.1}, {"simplify", true}};
  EXPECT_TRUE(parse_scene(j, ".", "s.json").mesh.simplify_surface);
  j["mesh"] = {{"box", {1, 1, 1}}, {"cells", {1, 1, 1}}, {"simplify", true}};
  EXPECT_THROW(parse_scene(j, ".", "s.json"), InputError);
}

TEST(Scene, MultigridKeysOfAnotherSolverAreIgnoredWithAWarning) {
  // A scene that sweeps solvers keeps its multigrid settings when it switches to CHOLMOD.
  auto j = minimal();
  j["analysis"] = {
      {"solver", "cholmod"}, {"levels", 4}, {"smoothing", 2}, {"hierarchy", "lattice"}};
  testing::internal::CaptureStderr();
  const Scene s = parse_scene(j, "/", "s.json");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(s.analysis.multigrid.hierarchy.levels, 1);
  EXPECT_NE(
      err.find(
          "analysis.levels, analysis.smoothing, analysis.hierarchy belong to multigrid solvers"),
      std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;  // one line
}

TEST(Scene, TheStationaryMultigridRefactorsItsCoarsestLevelAtEveryUpdateByDefault) {
  // Without CG around it, a kept coarsest factor's stale coarse solve made the lattice dragon's
  // two V-cycles worse than one (rel. error 0.156 against 0.070; refactored: 0.020): the
  // stationary multigrid's default is 0, MG-PCG's the solver's own (3%), a value given is kept.
  const auto refactor = [](const nlohmann::json& analysis) {
    auto j = minimal();
    j["analysis"] = analysis;
    return parse_scene(j, "/", "s.json").analysis.multigrid.coarsest_refactor_change;
  };
  EXPECT_EQ(refactor({{"solver", "multigrid"}}), 0.0);
  EXPECT_EQ(refactor({{"solver", "mgpcg"}}), MultigridParams{}.coarsest_refactor_change);
  EXPECT_GT(MultigridParams{}.coarsest_refactor_change, 0.0);
  EXPECT_EQ(refactor({{"solver", "multigrid"}, {"coarsest_refactor", 0.05}}), 0.05);
}

TEST(Scene, PetscMgRefusesTheSettingsItCannotHonour) {
  // PETSc's PCMG takes our levels, hierarchy and smoothing count; its own smoother, cycle and
  // Galerkin product are not ours to choose: a scene that asks for them is refused, naming the key.
  // Every key spelled out here, not read from the production list: a key dropped from that list
  // must fail this gate; and the two lists are the same (a key added there is spelled here).
  const std::vector<std::pair<std::string, nlohmann::json>> refused = {
      {"smoother", "chebyshev"}, {"cycle", "W"},          {"galerkin", "stream"},
      {"vcycles", 20},           {"chebyshev_degree", 3}, {"coarsest_refactor", 0.1},
      {"galerkin_refresh", 0.05}};
  std::set<std::string> spelled;
  for (const auto& entry : refused) spelled.insert(entry.first);
  const std::vector<std::string> production = keys_petsc_mg_cannot_honour();
  EXPECT_EQ(spelled, std::set<std::string>(production.begin(), production.end()));
  for (const auto& [key, value] : refused) {
    auto j = minimal();
    j["analysis"] = {{"solver", "petsc-mg"}, {"levels", 2}, {key, value}};
    try {
      parse_scene(j, "/", "s.json");
      ADD_FAILURE() << "analysis." << key << " accepted with petsc-mg";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("analysis." + key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("petsc-mg"), std::string::npos) << e.what();
    }
    // A tool that switches a multigrid scene to petsc-mg drops them instead.
    nlohmann::json analysis = {{"solver", "petsc-mg"}, {"levels", 2}, {key, value}};
    drop_unused_multigrid_keys(analysis);
    EXPECT_FALSE(analysis.contains(key)) << key;
    EXPECT_EQ(analysis["levels"], 2);
  }
  // What it honours still parses.
  auto j = minimal();
  j["analysis"] = {
      {"solver", "petsc-mg"}, {"levels", 2}, {"smoothing", 2}, {"hierarchy", "lattice"}};
  EXPECT_EQ(parse_scene(j, "/", "s.json").analysis.multigrid.pre_smoothing, 2);
}

TEST(Scene, CoarseMeshesAndHierarchy) {
  auto j = minimal();
  j["mesh"]["levels"] = {{{"box", {1, 0.1, 0.1}}, {"cells", {2, 1, 1}}}, {{"file", "c.msh"}}};
  j["analysis"] = {{"solver", "mgpcg"}};
  Scene s = parse_scene(j, "/base", "s.json");
  ASSERT_EQ(s.mesh.levels.size(), 2u);
  EXPECT_EQ(s.mesh.levels[0].kind, MeshSpec::Kind::Box);
  EXPECT_EQ(s.mesh.levels[1].path, std::filesystem::path("/base/c.msh"));
  EXPECT_EQ(s.analysis.multigrid.hierarchy.kind,
            HierarchyKind::Meshes);  // the default where coarse meshes exist
  // A mesh file without coarse meshes cannot be re-meshed: lattice by default, meshes refused.
  j = minimal();
  j["mesh"] = {{"file", "a.msh"}};
  j["analysis"] = {{"solver", "multigrid"}};
  EXPECT_EQ(parse_scene(j, "/", "s.json").analysis.multigrid.hierarchy.kind,
            HierarchyKind::Lattice);
  j["analysis"]["hierarchy"] = "meshes";
  EXPECT_THROW(parse_scene(j, "/", "s.json"), InputError);
}

struct BadCase {
  const char* name;
  const char* patch;     // JSON merge patch applied to the minimal scene
  const char* fragment;  // must appear in the message
};

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class BadScenes : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScenes, ErrorNamesTheKey) {
  auto j = minimal();
  j.merge_patch(nlohmann::json::parse(GetParam().patch));
  try {
    parse_scene(j, "/", "bad.json");
    ADD_FAILURE() << "accepted " << GetParam().patch;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.json"), std::string::npos) << what;
    EXPECT_NE(what.find(GetParam().fragment), std::string::npos) << what;
  }
}

const BadCase kBadCases[] = {
    {"UnknownTopKey", R"({"meshh": 1})", "meshh is not a known key"},
    {"UnknownNestedKey", R"({"analysis": {"dtt": 1}})", "analysis.dtt is not a known key"},
    {"YoungNotPositive", R"({"material": {"young": 0}})",
     "material.young must be in [1e-09, 1e+15]"},
    {"PoissonTooHigh", R"({"material": {"poisson": 0.5}})",
     "material.poisson must be in (-1, 0.5)"},
    {"PoissonWrongType", R"({"material": {"poisson": "0.3"}})",
     "material.poisson must be a number"},
    {"DensityNegative", R"({"material": {"density": -1}})",
     "material.density must be in [1e-09, 1e+09]"},
    {"DtZero", R"({"analysis": {"dt": 0}})", "analysis.dt must be in [1e-09, 1e+06]"},
    {"StepsNotInteger", R"({"analysis": {"steps": 1.5}})", "analysis.steps must be an integer"},
    {"UnknownType", R"({"analysis": {"type": "modal"}})", "analysis.type must be one of"},
    {"UnknownRotation", R"({"analysis": {"rotation": "magic"}})",
     "analysis.rotation must be one of"},
    {"UnknownSolver", R"({"analysis": {"solver": "magic"}})", "analysis.solver must be one of"},
    {"BoxInverted", R"({"fixed": [{"box": [[1, 0, 0], [0, 1, 1]]}]})",
     "fixed[0].box has a lower corner"},
    {"ForceWithoutTotal", R"({"forces": [{"box": [[0, 0, 0], [1, 1, 1]]}]})",
     "forces[0].total is required"},
    {"GravityShort", R"({"gravity": [0, -9.81]})", "gravity must be an array of 3 numbers"},
    {"CellsZero", R"({"mesh": {"cells": [0, 1, 1]}})", "mesh.cells must be 3 integers"},
    {"CellsHuge", R"({"mesh": {"cells": [100000, 100000, 100000]}})",
     "mesh.cells would give about 6e+15 tets"},
    {"TwoMeshSources", R"({"mesh": {"file": "a.msh"}})", "mesh.file must be given alone"},
    {"SurfaceWithoutSize", R"({"mesh": {"box": null, "cells": null, "surface": "a.stl"}})",
     "mesh.size is required"},
    {"GravityNeedsDensity", R"({"gravity": [0, 0, -9.81]})", "material.density is required"},
    {"DynamicNeedsDensity", R"({"analysis": {"type": "dynamic"}})", "material.density is required"},
    {"OutputRotationsType", R"({"output": {"rotations": 1}})",
     "output.rotations must be true or false"},
    {"UnknownStart", R"({"analysis": {"start": "guess"}})", "analysis.start must be one of"},
    {"UnknownFactorization", R"({"analysis": {"factorization": "dense"}})",
     "analysis.factorization must be one of"},
    {"StartHistoryOfOne", R"({"analysis": {"start_history": 1}})",
     "analysis.start_history must be in [2, 16]"},
    {"LevelsOutOfRange", R"({"analysis": {"levels": 17}})", "analysis.levels must be in [1, 16]"},
    {"UnknownHierarchy", R"({"analysis": {"solver": "mgpcg", "hierarchy": "octree"}})",
     "analysis.hierarchy must be one of"},
    {"CoarseMeshUnknownKey",
     R"({"mesh": {"levels": [{"box": [1, 1, 1], "cells": [2, 1, 1], "colour": 1}]}})",
     "mesh.levels[0].colour is not a known key"},
    {"CoarseMeshTwoSources",
     R"({"mesh": {"levels": [{"box": [1, 1, 1], "cells": [2, 1, 1], "file": "c.msh"}]}})",
     "mesh.levels[0].file must be given alone"},
};

INSTANTIATE_TEST_SUITE_P(Cases, BadScenes, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace corofem
