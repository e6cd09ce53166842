// `corofem tune`: the error between runs on different meshes against affine fields (which the
// point location reproduces exactly); the time step's scaling; and the tool end to end: it meets
// a target on a small scene, checked by an independent run of the scene it writes against the
// exact solve, and it refuses a target below the reference's own discretization error.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "mesh/box_mesh.hpp"
#include "scene/load_schedule.hpp"
#include "scene/scene_simulation.hpp"
#include "scene/time_step_scaling.hpp"
#include "test_support.hpp"
#include "tune/tune_axes.hpp"
#include "tune/tune_quantity.hpp"

namespace corofem {
namespace {

using nlohmann::json;
using test::run_cli;
using test::TempDir;
using test::write_text;

/// The state of `mesh` under the displacement u(x) = A x + b.
FinalState affine_state(TetMesh mesh, const Mat3& a, const Vec3& b) {
  Eigen::VectorXd u(3 * mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) u.segment<3>(3 * v) = a * mesh.rest[v] + b;
  return {std::move(mesh), std::move(u)};
}

TEST(TuneQuantity, AffineFieldsAgreeAcrossNonNestedMeshes) {
  Mat3 a;
  a << 0.1, -0.02, 0.03, 0.01, 0.05, -0.04, 0.02, 0.03, -0.06;
  const Vec3 b(0.01, -0.02, 0.005);
  const Vec3 size(1.0, 0.3, 0.2);
  const FinalState fine = affine_state(make_box_mesh(size, {9, 4, 3}), a, b);
  const FinalState coarse = affine_state(make_box_mesh(size, {5, 2, 2}), a, b);
  // Interpolation reproduces affine fields: the error is round-off (1e-12 of |u| ~ 0.1).
  for (const TuneQuantity kind :
       {TuneQuantity::Displacement, TuneQuantity::Tip, TuneQuantity::Probe}) {
    QuantitySpec q{.kind = kind,
                   .probe = {Vec3(0.6, 0, 0), Vec3(1.0, 0.3, 0.2)},
                   .tip = tip_point(fine, {AxisBox{Vec3::Zero(), Vec3(0, 0.3, 0.2)}})};
    EXPECT_LT(quantity_error(q, coarse, fine), 1e-12) << kTuneQuantities.name(kind);
    EXPECT_LT(quantity_error(q, fine, coarse), 1e-12) << kTuneQuantities.name(kind);
  }
  // The tip: the vertex farthest from the support at x = 0, a corner of the far end.
  const Vec3 tip = tip_point(fine, {AxisBox{Vec3::Zero(), Vec3(0, 0.3, 0.2)}});
  EXPECT_DOUBLE_EQ(tip.x(), 1.0);
  // A field 1% larger everywhere is 1% off, on the same mesh and across meshes.
  FinalState larger = coarse;
  larger.displacement *= 1.01;
  const QuantitySpec field{};
  EXPECT_NEAR(quantity_error(field, larger, coarse), 0.01, 1e-12);
  EXPECT_NEAR(quantity_error(field, larger, fine), 0.01, 1e-12);
}

TEST(TuneAxes, TimeStepScalingKeepsTheEndTimeOrRefuses) {
  const json scene = {{"analysis", {{"dt", 0.01}, {"steps", 40}}},
                      {"forces", {{{"ramp_steps", 10}, {"release_step", 20}}}}};
  const auto coarser = time_step_scaled(scene, 2, 1);
  ASSERT_TRUE(coarser);
  EXPECT_DOUBLE_EQ((*coarser)["analysis"]["dt"].get<double>(), 0.02);
  EXPECT_EQ((*coarser)["analysis"]["steps"], 20);
  EXPECT_EQ((*coarser)["forces"][0]["ramp_steps"], 5);
  EXPECT_EQ((*coarser)["forces"][0]["release_step"], 10);
  EXPECT_FALSE(time_step_scaled(scene, 4, 1));  // a ramp of 10 steps is not 2.5 steps of 4 dt
  const auto finer = time_step_scaled(scene, 1, 3);
  ASSERT_TRUE(finer);
  EXPECT_EQ((*finer)["analysis"]["steps"], 120);
  EXPECT_EQ((*finer)["forces"][0]["ramp_steps"], 30);
}

/// A small dynamic bar sagging under gravity: polar rotations, MG-PCG at 1e-6 (over-delivering
/// for a target of 1e-3).
const char* kDynamicBar = R"({
  "mesh": {"box": [1, 0.2, 0.2], "cells": [10, 2, 2]},
  "material": {"young": 2e5, "poisson": 0.3, "density": 1000},
  "fixed": [{"box": [[0, 0, 0], [0, 0.2, 0.2]]}],
  "forces": [{"box": [[0.9, 0, 0], [1, 0.2, 0.2]], "total": [0, 0, -40], "ramp_steps": 4}],
  "analysis": {"type": "dynamic", "formulation": "corotational", "rotation": "polar",
               "solver": "mgpcg", "levels": 2, "tolerance": 1e-6, "dt": 0.01, "steps": 8,
               "rayleigh": {"alpha": 1.0}},
  "output": {"vtu": "bar.vtu"}
})";

Eigen::VectorXd final_displacement(const json& scene, const std::filesystem::path& dir) {
  SceneSimulation simulation(parse_scene(scene, dir, "scene"));
  const SimulationResult result = simulation.run();
  EXPECT_TRUE(result.converged) << result.message;
  return result.displacement;
}

TEST(Tune, MeetsATargetCheckedAgainstTheExactSolveOfTheSceneItWrites) {
  TempDir dir;
  write_text(dir / "bar.json", kDynamicBar);
  const double target = 1e-3;
  const auto r = run_cli("tune '" + (dir / "bar.json").string() + "' --target 1e-3 --resolution " +
                         "fixed --budget 3 --no-render --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("tune: met"), std::string::npos) << r.err;
  const json tuned = json::parse(test::read_text(dir / "out" / "tuned_scene.json"));
  const json record = json::parse(test::read_text(dir / "out" / "tune.json"));
  EXPECT_EQ(record["answer"]["status"], "met");
  EXPECT_FALSE(tuned.contains("output"));  // the search's runs write nothing
  // The oracle: CHOLMOD with the exact rotation minimizer on the same mesh, run here.
  json exact = json::parse(kDynamicBar);
  exact.erase("output");
  exact["analysis"]["rotation"] = "energy-exact";
  exact["analysis"]["solver"] = "cholmod";
  drop_unused_multigrid_keys(exact["analysis"]);
  const Eigen::VectorXd u_exact = final_displacement(exact, dir.path());
  const Eigen::VectorXd u_tuned = final_displacement(tuned, dir / "out");
  ASSERT_EQ(u_tuned.size(), u_exact.size());
  const double error = (u_tuned - u_exact).norm() / u_exact.norm();
  EXPECT_LE(error, target);
  // The record's re-run says the same, to round-off of the norms.
  EXPECT_NEAR(record["answer"]["rerun"]["error"].get<double>(), error, 1e-9 + 1e-6 * error);
  // A search, not a grid; every completed candidate with its cost, a Pareto front.
  EXPECT_LE(record["runs"].get<double>(), 0.25 * record["full_grid_runs"].get<double>());
  int front = 0;
  for (const json& c : record["candidates"])
    if (c["completed"].get<bool>()) {
      EXPECT_GT(c["cost_ms"].get<double>(), 0);
      front += c.value("pareto", false);
    }
  EXPECT_GE(front, 1);
  for (const char* key : {"context", "scene", "axes", "reference_error", "given"})
    EXPECT_TRUE(record.contains(key)) << key;
}

/// A stubby bar bent under gravity on 3 cells through its depth: linear tets are far from
/// converged in bending (the reference's own error is tens of percent).
const char* kBentBar = R"({
  "mesh": {"box": [1, 0.2, 0.2], "cells": [10, 2, 2]},
  "material": {"young": 1e6, "poisson": 0.3, "density": 1000},
  "fixed": [{"box": [[0, 0, 0], [0, 0.2, 0.2]]}],
  "gravity": [0, 0, -9.81],
  "analysis": {"type": "static", "formulation": "corotational", "rotation": "polar",
               "solver": "cholmod", "load_steps": 2, "tolerance": 1e-8}
})";

/// The solver axis `corofem tune` searches for the scene `raw` (resolution fixed), if any.
std::optional<TuneAxis> solver_axis(const json& raw, const std::filesystem::path& dir) {
  const Scene scene = parse_scene(raw, dir, "bent.json");
  std::string note;
  for (TuneAxis& axis : tune_axes(scene, raw, {.resolution_free = false}, note))
    if (axis.name == "solver") return axis;
  return std::nullopt;
}

TEST(TuneAxes, StaticNewtonOffersTheMultigridTangentWhereTheSceneFactorsIt) {
  // The bent bar on cholmod factors its Newton tangent: the solver axis holds Newton's tolerances
  // on the scene's own solver (the reference and the given value first) and on mgpcg. On mgpcg
  // the scene already solves its tangent on the multigrid: its own family alone.
  TempDir dir;
  for (const char* solver : {"cholmod", "mgpcg"}) {
    SCOPED_TRACE(solver);
    json raw = json::parse(kBentBar);
    raw["analysis"]["solver"] = solver;
    const std::optional<TuneAxis> axis = solver_axis(raw, dir.path());
    ASSERT_TRUE(axis);
    std::map<std::string, int> families;
    for (const AxisValue& v : axis->values) ++families[v.family];
    EXPECT_EQ(families["newton"], 5);
    EXPECT_EQ(families["newton mgpcg"], std::string(solver) == "cholmod" ? 5 : 0);
    EXPECT_EQ(axis->reference, 0);
    EXPECT_EQ(axis->given, 0);
    for (const AxisValue& v : axis->values)
      if (v.family == "newton mgpcg") {
        // Each value is a scene that runs as it is: it parses, on mgpcg, at its tolerance.
        json patched = raw;
        patched.merge_patch(v.patch);
        const Scene s = parse_scene(patched, dir.path(), "bent.json");
        EXPECT_EQ(s.analysis.solver, SolverKind::Mgpcg) << v.label;
        EXPECT_EQ(s.analysis.tolerance, v.patch["analysis"]["tolerance"].get<double>());
      }
  }
}

TEST(TuneAxes, ProjectedStartsAreCandidatesWhereAStartCounts) {
  // A dynamic corotated run (linearly implicit) starts each solve from its last velocities: the
  // solver axis offers the iterative solvers started from their projection, each a scene that
  // parses to that start (the record's analysis.start then says projection). The lagged static
  // iteration solves no sequence of steps: no such candidates.
  TempDir dir;
  for (const char* type : {"dynamic", "static"}) {
    SCOPED_TRACE(type);
    json raw = json::parse(kBentBar);
    raw["analysis"] = {{"type", type},
                       {"formulation", "corotational"},
                       {"solver", "cholmod"},
                       {"integrator", "linear-implicit"}};
    if (std::string(type) == "dynamic") raw["analysis"]["steps"] = 4;
    const std::optional<TuneAxis> axis = solver_axis(raw, dir.path());
    ASSERT_TRUE(axis);
    std::map<std::string, int> families;
    for (const AxisValue& v : axis->values) {
      ++families[v.family];
      if (v.family.find("projected start") == std::string::npos) continue;
      json patched = raw;
      patched.merge_patch(v.patch);
      const Scene s = parse_scene(patched, dir.path(), "bent.json");
      EXPECT_EQ(s.analysis.start, SolveStart::Projection) << v.label;
      EXPECT_GT(projected_start_history(s.analysis, false), 0) << v.label;
    }
    const int expected = std::string(type) == "dynamic" ? 3 : 0;
    EXPECT_EQ(families["mgpcg projected start"], expected);
    EXPECT_EQ(families["jacobi-pcg projected start"], expected);
  }
}

TEST(Tune, RefusesATargetBelowTheReferencesOwnError) {
  TempDir dir;
  write_text(dir / "bent.json", kBentBar);
  const auto r = run_cli("tune '" + (dir / "bent.json").string() +
                         "' --target 1e-3 --no-render --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json record = json::parse(test::read_text(dir / "out" / "tune.json"));
  EXPECT_EQ(record["answer"]["status"], "refused");
  EXPECT_NE(record["answer"]["reason"].get<std::string>().find("discretization-limited"),
            std::string::npos);
  EXPECT_GT(record["reference_error"]["value"].get<double>(), 1e-3);
  // The reference is the finer mesh, and its error estimate comes from a coarser one.
  EXPECT_GT(record["reference_error"]["tets"][0].get<int>(),
            record["reference_error"]["tets"][1].get<int>());
}

TEST(Tune, BadOptionsExit2AndWriteNothing) {
  TempDir dir;
  write_text(dir / "bent.json", kBentBar);
  const std::string scene =
      std::string("'") + (dir / "bent.json").string() + "'";  // as in cli_mpi_test
  const std::string out = " --out '" + (dir / "out").string() + "'";
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"--target 2", "--target must be in (0, 1)"},
           {"--target abc", "--target needs a number"},
           {"", "tune needs --target"},
           {"--target 1e-2 --quantity probe", "--probe BOX goes with --quantity probe"},
           {"--target 1e-2 --quantity probe --probe 1,2,3", "--probe needs 6 numbers"},
           {"--target 1e-2 --quantity mass", "--quantity must be"},
           {"--target 1e-2 --resolution coarse", "--resolution must be free or fixed"}}) {
    const auto r = run_cli("tune " + scene + " " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "tune.json")) << args;
  }
}

}  // namespace
}  // namespace corofem
