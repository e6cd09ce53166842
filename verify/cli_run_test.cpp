// The CLI end to end: a run writes the documented record; every bad input exits 2 with a message
// naming the file, key or element, and leaves no output file behind.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <vector>

#include "fem/corotated_assembly.hpp"
#include "fem/dirichlet.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene_simulation.hpp"
#include "solver/petsc_solver.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::run_cli;
using test::TempDir;
using test::write_text;

const char* kScene = R"({
  "mesh": {"box": [1, 0.1, 0.1], "cells": [10, 1, 1]},
  "material": {"young": 5e6, "poisson": 0.3, "density": 1000},
  "fixed": [{"box": [[0, 0, 0], [0, 0.1, 0.1]]}],
  "gravity": [0, 0, -9.81],
  "analysis": {"type": "static", "formulation": "corotational", "rotation": "polar",
               "load_steps": 4, "tolerance": 1e-9},
  "output": {"rotations": true, "vtu": "bar.vtu"}
})";

TEST(CliRun, VersionNamesTheReleaseAndTheCommit) {
  const auto r = run_cli("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // "corofem 0.1.0 (commit <40 hex digits>[-dirty], <compiler>, <build type> <flags>)"
  EXPECT_TRUE(std::regex_search(
      r.out, std::regex(R"(^corofem [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]{40}(-dirty)?, )")))
      << r.out;
}

TEST(CliRun, WritesTheDocumentedRecord) {
  TempDir dir;
  write_text(dir / "bar.json", kScene);
  const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                         (dir / "result.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("converged"), std::string::npos);  // progress on stderr
  const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
  for (const char* key :
       {"node_tags", "rest", "displacement", "converged", "iterations", "residual", "timings_ms",
        "scene", "context", "element_tags", "rotations"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"commit", "compiler", "flags", "cpu"})
    EXPECT_TRUE(j["context"].contains(key)) << key;
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_LT(j["residual"].get<double>(), 1e-9);
  const std::size_t nv = j["node_tags"].size();
  EXPECT_EQ(nv, 2u * 2u * 11u);
  EXPECT_EQ(j["rest"].size(), nv);
  EXPECT_EQ(j["displacement"].size(), nv);
  EXPECT_EQ(j["rotations"].size(), j["element_tags"].size());
  EXPECT_TRUE(std::filesystem::exists(dir / "bar.vtu"));

  // The record against the scene rebuilt in this process (its mesh, masses and forces). JSON keeps
  // doubles to the last bit, so the record's numbers are the run's.
  SceneSimulation sim(parse_scene(nlohmann::json::parse(kScene), dir.path().string(), "bar.json"));
  FeProblem& p = sim.problem();
  ASSERT_EQ(static_cast<int>(nv), p.mesh.num_vertices());
  ASSERT_EQ(static_cast<int>(j["rotations"].size()), p.mesh.num_tets());
  Eigen::VectorXd u(p.num_dofs());
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(j["rest"][v][c].get<double>(), p.mesh.rest[v][c]) << "vertex " << v;
      u[3 * v + c] = j["displacement"][v][c].get<double>();
    }
  const std::vector<Vec3> x = p.positions(u);
  // Each rotation is the polar factor of its element's deformation gradient F (the scene's
  // method): unit, proper, and Q^T F symmetric to the rounding of F's entries (|F| ~ 1).
  for (int e = 0; e < p.mesh.num_tets(); ++e) {
    const auto& q = j["rotations"][e];
    const Eigen::Quaterniond quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(),
                                  q[3].get<double>());
    EXPECT_NEAR(quat.norm(), 1.0, 1e-12) << "element " << e;
    const Tet& t = p.mesh.tets[e];
    Mat3 rest_edges, edges;
    for (int k = 0; k < 3; ++k) {
      rest_edges.col(k) = p.mesh.rest[t[k + 1]] - p.mesh.rest[t[0]];
      edges.col(k) = x[t[k + 1]] - x[t[0]];
    }
    const Mat3 f = edges * rest_edges.inverse();
    const Mat3 stretch = quat.normalized().toRotationMatrix().transpose() * f;
    EXPECT_LT((stretch - stretch.transpose()).norm(), 1e-9 * f.norm()) << "element " << e;
    EXPECT_GT(stretch.determinant(), 0) << "element " << e;
  }
  // The displacement is the equilibrium: f_int(u) (polar rotations of u) balances gravity (the
  // lumped masses times g) on the free DOFs to the run's tolerance, 1e-9; 1e-8 leaves room for
  // the summation order of the forces recomputed here.
  std::vector<Mat3> polar(p.mesh.tets.size(), Mat3::Identity());
  make_rotation_extractor(RotationMethod::Polar, p.mesh)->extract(x, polar);
  Eigen::VectorXd gravity(p.num_dofs());
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    gravity.segment<3>(3 * v) = p.mass.segment<3>(3 * v).cwiseProduct(Vec3(0, 0, -9.81));
  const double imbalance = free_norm(p.dirichlet, gravity - internal_forces(p, polar, u)) /
                           free_norm(p.dirichlet, gravity);
  EXPECT_LT(imbalance, 1e-8);
  // And it is not the rest state: the free end hangs down.
  EXPECT_LT(u.minCoeff(), -1e-4);
}

struct BadRun {
  const char* name;
  const char* scene;     // scene text; empty: no scene file
  const char* fragment;  // in stderr
};

void PrintTo(const BadRun& c, std::ostream* os) {
  *os << c.name;
}

class CliBadInput : public ::testing::TestWithParam<BadRun> {};

TEST_P(CliBadInput, ExitsTwoNamesTheFaultAndWritesNothing) {
  TempDir dir;
  const auto scene = dir / "scene.json";
  if (*GetParam().scene) write_text(scene, GetParam().scene);
  const auto out = dir / "result.json";
  const auto r = run_cli("run '" + scene.string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().fragment), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

const BadRun kBadRuns[] = {
    {"MissingScene", "", "does not exist"},
    {"NotJson", "{ mesh: ", "is not valid JSON"},
    {"UnknownKey",
     R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3}, "colour": 1})",
     "colour is not a known key"},
    {"MissingMeshFile",
     R"({"mesh": {"file": "nope.msh"}, "material": {"young": 1, "poisson": 0.3}})",
     "nope.msh' does not exist"},
    {"FixedSelectsNothing",
     R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3},
       "fixed": [{"box": [[5,5,5],[6,6,6]]}]})",
     "fixed[0].box selects no vertex"},
    {"RigidMotionFree",
     R"({"mesh": {"box": [1,1,1], "cells": [2,2,2]}, "material": {"young": 1, "poisson": 0.3},
       "fixed": [{"box": [[0,0,0],[0,0,1]]}]})",
     "leaves rigid motions free"},
    {"NumberOverflow",
     R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": -1e400, "poisson": 0.3}})",
     "key 'young' is outside the range of a double"},
    {"AutoSolverOnACorotatedNewtonTangent",
     R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3},
       "fixed": [{"box": [[0,0,0],[0,1,1]]}],
       "analysis": {"type": "static", "formulation": "corotational", "solver": "auto"}})",
     "analysis.solver must be a named solver with integrator 'newton'"},
    {"NoSupportsStatic",
     R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3}})",
     "leaves rigid motions free"},
};

INSTANTIATE_TEST_SUITE_P(Cases, CliBadInput, ::testing::ValuesIn(kBadRuns),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(CliRun, StaticSceneNeedsEveryPartOfTheBodyHeld) {
  // One STL, two separate cubes, only the first fixed: static, the second is free to move
  // rigidly and its stiffness singular. The error names that part and where it is (Newton said
  // only "the tangent matrix is singular"). The same scene, dynamic, runs: the free cube falls.
  TempDir dir;
  write_text(dir / "two.stl", test::cube_stl(2) + test::cube_stl(2, Vec3(2, 0, 0)));
  nlohmann::json scene = {{"mesh", {{"surface", "two.stl"}, {"size", 0.5}}},
                          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
                          {"fixed", {{{"box", {{-1, -1, -1}, {1.5, 2, 1e-6}}}}}},
                          {"gravity", {0, 0, -9.81}},
                          {"analysis", {{"type", "static"}}}};
  write_text(dir / "static.json", scene.dump());
  auto r = run_cli("run '" + (dir / "static.json").string() + "' --out '" +
                   (dir / "static_result.json").string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("leaves rigid motions free on part 2 of the 2 separate parts"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("around (2."), std::string::npos) << r.err;  // the second cube, x in [2, 3]
  scene["analysis"] = {{"type", "dynamic"}, {"steps", 2}};
  write_text(dir / "dynamic.json", scene.dump());
  r = run_cli("run '" + (dir / "dynamic.json").string() + "' --out '" +
              (dir / "dynamic_result.json").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(CliRun, UnwritableOutputIsBadInput) {
  TempDir dir;
  write_text(dir / "bar.json", kScene);
  const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                         (dir / "no/such/dir/result.json").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot write output file"), std::string::npos) << r.err;
}

TEST(CliRun, NonConvergenceExitsOneAndSaysSo) {
  TempDir dir;
  auto scene = nlohmann::json::parse(kScene);
  scene["analysis"]["max_iterations"] = 1;
  scene["analysis"]["load_steps"] = 1;
  scene["analysis"]["tolerance"] = 1e-14;
  write_text(dir / "bar.json", scene.dump());
  const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                         (dir / "result.json").string() + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("tolerance 1e-14"), std::string::npos) << r.err;  // %g, not 0.000000
  const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
  EXPECT_FALSE(j["converged"].get<bool>());
}

TEST(CliRun, StaticDefaultsConvergeForEveryRotationMethod) {
  // A 20 x 2 x 2 cantilever, 2 m long, sagging under gravity by three quarters of its length,
  // with nothing but the rotation method set: the static default (Newton, one load increment,
  // halved where its full steps do not converge) reaches the default tolerance, 1e-8, for every
  // method. (The lagged iteration ran out of iterations here for energy-newton; one increment
  // of full Newton steps diverges for qr.)
  for (const std::string& method : rotation_method_names()) {
    if (method == "none") continue;
    SCOPED_TRACE(method);
    TempDir dir;
    const nlohmann::json scene = {
        {"mesh", {{"box", {2.0, 0.2, 0.2}}, {"cells", {20, 2, 2}}}},
        {"material", {{"young", 1e6}, {"poisson", 0.3}, {"density", 1000}}},
        {"fixed", {{{"box", {{0, 0, 0}, {0, 0.2, 0.2}}}}}},
        {"gravity", {0, 0, -9.81}},
        {"analysis", {{"type", "static"}, {"rotation", method}}}};
    write_text(dir / "bar.json", scene.dump());
    const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                           (dir / "r.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(test::read_text(dir / "r.json"));
    EXPECT_TRUE(j["converged"].get<bool>());
    EXPECT_LT(j["residual"].get<double>(), 1e-8);
    EXPECT_EQ(j["analysis"]["integrator"], "newton");
    double lowest = 0;
    for (const auto& u : j["displacement"]) lowest = std::min(lowest, u[2].get<double>());
    EXPECT_LT(lowest, -1.0) << "the tip sags far: the test needs a large deformation";
  }
}

TEST(CliRun, StaticNewtonOnTheMultigridRecordsTangentsTakenOnTheDefiniteStandIn) {
  // The gallery's soft column bent by tilted gravity (bench/scenes/column_static_newton_mgpcg.json;
  // fem_newton_test: its tangent's symmetric part turns indefinite on the way): on mgpcg the record
  // names the tangent's path and counts the tangents preconditioned on the corotated stiffness (at
  // least one) and those factored (none).
  TempDir dir;
  const auto r = run_cli(
      "run '" + (test::source_dir() / "bench/scenes/column_static_newton_mgpcg.json").string() +
      "' --out '" + (dir / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_text(dir / "r.json"));
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_GE(j["tangent_standin_solves"].get<int>(), 1);
  EXPECT_EQ(j["tangent_factored_solves"].get<int>(), 0);
  EXPECT_NE(j["analysis"]["solver"].get<std::string>().find("corotated stiffness"),
            std::string::npos)
      << j["analysis"]["solver"];
}

TEST(CliRun, RivalSolverRunsWhereBuiltAndIsBadInputWhereNot) {
  // petsc-gamg on the static bar: where this build has PETSc it runs and converges; where it does
  // not (the sanitizer build leaves it out), the scene is bad input naming the solver and the
  // library, and no output file is written.
  TempDir dir;
  auto scene = nlohmann::json::parse(kScene);
  scene["analysis"]["solver"] = "petsc-gamg";
  scene["analysis"]["formulation"] = "linear";
  scene.erase("output");
  write_text(dir / "bar.json", scene.dump());
  const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                         (dir / "result.json").string() + "'");
  if (have_petsc()) {
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
    EXPECT_TRUE(j["converged"].get<bool>());
    EXPECT_EQ(j["scene"]["analysis"]["solver"], "petsc-gamg");
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("'petsc-gamg' needs PETSc"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "result.json"));
  }
}

TEST(CliRun, PetscMgOnOneLevelIsItsLuAndEqualsCholmod) {
  // petsc-mg asked for one level has no coarse operators to make: its one level's LU solves,
  // and the answer is CHOLMOD's (a crash before this gate's fix: the coarse operators read a
  // transfer that did not exist).
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc";
  TempDir dir;
  auto scene = nlohmann::json::parse(kScene);
  scene["analysis"]["formulation"] = "linear";
  scene["analysis"]["tolerance"] = 1e-10;
  scene.erase("output");
  std::vector<double> u[2];
  const char* solvers[2] = {"cholmod", "petsc-mg"};
  for (int s = 0; s < 2; ++s) {
    scene["analysis"]["solver"] = solvers[s];
    if (s == 1) scene["analysis"]["levels"] = 1;
    write_text(dir / "bar.json", scene.dump());
    const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                           (dir / "result.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << solvers[s] << ": " << r.err;
    const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
    for (const auto& d : j["displacement"])
      for (int c = 0; c < 3; ++c) u[s].push_back(d[c].get<double>());
  }
  ASSERT_EQ(u[0].size(), u[1].size());
  double largest = 0, difference = 0;
  for (std::size_t k = 0; k < u[0].size(); ++k) {
    largest = std::max(largest, std::abs(u[0][k]));
    difference = std::max(difference, std::abs(u[0][k] - u[1][k]));
  }
  ASSERT_GT(largest, 0);
  // An LU-preconditioned CG to 1e-10 of |b|: the displacements agree to about that.
  EXPECT_LT(difference, 1e-8 * largest);
}

/// The largest difference of two records' displacements (per vertex, 3 components) over the
/// reference's largest component; infinite where the reference does not move (nothing compared).
double displacement_difference(const nlohmann::json& u, const nlohmann::json& reference) {
  EXPECT_EQ(u.size(), reference.size());
  double largest = 0, difference = 0;
  for (std::size_t v = 0; v < std::min(u.size(), reference.size()); ++v)
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(reference[v][c].get<double>()));
      difference =
          std::max(difference, std::abs(u[v][c].get<double>() - reference[v][c].get<double>()));
    }
  return largest > 0 ? difference / largest : std::numeric_limits<double>::infinity();
}

/// A cube [0,1]^3 in Kuhn cells, fixed at x = 0, solved statically by multigrid on two levels;
/// the coarse level is `coarse` (a mesh spec).
nlohmann::json multigrid_cube(const nlohmann::json& coarse) {
  return {{"mesh", {{"box", {1, 1, 1}}, {"cells", {4, 4, 4}}, {"levels", {coarse}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {0, 1, 1}}}}}},
          {"gravity", {0, 0, -9.81}},
          {"analysis",
           {{"type", "static"},
            {"formulation", "linear"},
            {"solver", "multigrid"},
            {"levels", 2},
            {"tolerance", 1e-10}}}};
}

/// multigrid_cube's cube, dynamic and corotated on `solver` (two levels for the multigrid): 8
/// steps, each solve to 1e-10.
nlohmann::json dynamic_cube(const char* solver) {
  nlohmann::json scene = multigrid_cube({{"box", {1, 1, 1}}, {"cells", {2, 2, 2}}});
  scene["analysis"] = {{"type", "dynamic"}, {"formulation", "corotational"},
                       {"solver", solver},  {"levels", 2},
                       {"steps", 8},        {"tolerance", 1e-10}};
  return scene;
}

/// `scene` run by the CLI in `dir`: its record (null, and the test failed, on a non-zero exit).
nlohmann::json run_record(const TempDir& dir, const nlohmann::json& scene) {
  write_text(dir / "cube.json", scene.dump());
  const auto r = run_cli("run '" + (dir / "cube.json").string() + "' --out '" +
                         (dir / "r.json").string() + "'");
  if (r.exit_code != 0) {
    ADD_FAILURE() << r.err;
    return nullptr;
  }
  return nlohmann::json::parse(test::read_text(dir / "r.json"));
}

/// One ASCII gmsh 2.2 file with the given nodes (tags 1..n) and linear tets.
std::string msh_v2(const std::vector<std::array<double, 3>>& nodes,
                   const std::vector<std::array<int, 4>>& tets) {
  std::string s =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
  for (std::size_t i = 0; i < nodes.size(); ++i)
    s += std::to_string(i + 1) + " " + std::to_string(nodes[i][0]) + " " +
         std::to_string(nodes[i][1]) + " " + std::to_string(nodes[i][2]) + "\n";
  s += "$EndNodes\n$Elements\n" + std::to_string(tets.size()) + "\n";
  for (std::size_t e = 0; e < tets.size(); ++e)
    s += std::to_string(e + 1) + " 4 2 0 1 " + std::to_string(tets[e][0]) + " " +
         std::to_string(tets[e][1]) + " " + std::to_string(tets[e][2]) + " " +
         std::to_string(tets[e][3]) + "\n";
  return s + "$EndElements\n";
}

// gmsh is loaded at its first call (mesh/gmsh_api.hpp): a run on a box never maps its library,
// a run that meshes does and gets its mesh. The dynamic loader's own log (LD_DEBUG=files) lists
// every library a process maps, linked or loaded later.
TEST(CliRun, GmshIsLoadedOnlyByRunsThatMesh) {
  TempDir dir;
  const std::string loader_log = "env LD_DEBUG=files";
  write_text(dir / "bar.json", kScene);
  const auto box = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                               (dir / "bar_result.json").string() + "'",
                           loader_log);
  ASSERT_EQ(box.exit_code, 0) << box.err;
  EXPECT_NE(box.err.find("libcholmod"), std::string::npos) << "no loader log to read";
  EXPECT_EQ(box.err.find("libgmsh"), std::string::npos);

  nlohmann::json quadruped = nlohmann::json::parse(kScene);
  quadruped["mesh"] = {{"shape", "quadruped"}, {"size", 0.3}};
  quadruped["fixed"] = {{{"box", {{-1, -1, -1}, {3, 1, 0.05}}}}};  // the hooves
  quadruped.erase("output");
  write_text(dir / "quadruped.json", quadruped.dump());
  const auto meshed = run_cli("run '" + (dir / "quadruped.json").string() + "' --out '" +
                                  (dir / "quadruped_result.json").string() + "'",
                              loader_log);
  ASSERT_EQ(meshed.exit_code, 0) << meshed.err;
  EXPECT_NE(meshed.err.find("libgmsh"), std::string::npos);
  const auto j = nlohmann::json::parse(test::read_text(dir / "quadruped_result.json"));
  EXPECT_GT(j["node_tags"].size(), 30u);  // the quadruped gmsh meshed
}

TEST(CliRun, MultigridRecordDescribesTheHierarchy) {
  TempDir dir;
  write_text(dir / "cube.json", multigrid_cube({{"box", {1, 1, 1}}, {"cells", {2, 2, 2}}}).dump());
  const auto r = run_cli("run '" + (dir / "cube.json").string() + "' --out '" +
                         (dir / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_text(dir / "r.json"));
  const auto& mg = j["multigrid"];
  EXPECT_EQ(mg["hierarchy"], "meshes");
  ASSERT_EQ(mg["levels"].size(), 2u);
  EXPECT_EQ(mg["levels"][0]["vertices"], 125);  // 5^3 box vertices
  // 3^3 coarse vertices: those at x = 0 also interpolate the free fine vertices at x = 0.25.
  EXPECT_EQ(mg["levels"][1]["vertices"], 27);
  EXPECT_EQ(mg["levels"][1]["built_from"]["outside_points"], 0);  // same box: all inside
  // Blocks: the fine pattern plus the coarse one, over the fine one.
  const double blocks0 = mg["levels"][0]["blocks"], blocks1 = mg["levels"][1]["blocks"];
  EXPECT_NEAR(mg["operator_complexity"].get<double>(), (blocks0 + blocks1) / blocks0, 1e-12);
  EXPECT_GT(mg["rho"].get<double>(), 0.0);
  EXPECT_LT(mg["rho"].get<double>(), 1.0);
  EXPECT_GE(mg["iterations"].get<double>(), 1.0);
  for (const char* key : {"params", "setup_ms", "solves"}) EXPECT_TRUE(mg.contains(key)) << key;
  for (const char* key : {"hierarchy", "galerkin", "smoother", "cycle"})
    EXPECT_TRUE(mg["params"].contains(key)) << key;
}

TEST(CliRun, AProjectedStartIsRecordedAndSolvesTheSameSteps) {
  // A dynamic corotated run on MG-PCG, its solves started from the linear extrapolation (the
  // default) and from the projection (analysis.start): the record says which, and both runs
  // solve every step to 1e-10, so their displacements agree far inside 1e-6 of the largest.
  // CHOLMOD ignores a start: its record says extrapolation whatever the scene asks.
  TempDir dir;
  std::vector<nlohmann::json> records;
  for (const char* run : {"default", "projection", "cholmod"}) {
    nlohmann::json s = dynamic_cube(std::string(run) == "cholmod" ? "cholmod" : "mgpcg");
    if (std::string(run) != "default") s["analysis"]["start"] = "projection";
    records.push_back(run_record(dir, s));
    ASSERT_FALSE(records.back().is_null()) << run;
  }
  EXPECT_EQ(records[0]["analysis"]["start"], nlohmann::json({{"kind", "extrapolation"}}));
  EXPECT_EQ(records[1]["analysis"]["start"],
            nlohmann::json({{"kind", "projection"}, {"history", 4}}));
  EXPECT_EQ(records[2]["analysis"]["start"], nlohmann::json({{"kind", "extrapolation"}}));
  ASSERT_EQ(records[0]["displacement"].size(), 125u);  // per vertex, 5^3
  EXPECT_LT(displacement_difference(records[1]["displacement"], records[0]["displacement"]), 1e-6);
  // And it did start from the projection: a record that says so but extrapolated would take as
  // many CG iterations as the default.
  EXPECT_LT(records[1]["linear_iterations"].get<int>(), records[0]["linear_iterations"].get<int>());
}

TEST(CliRun, AnAutoSolverRecordsItsTrialAndKeepsTheCheaper) {
  // analysis.solver "auto" on a dynamic corotated cube: the record lists both candidates' trial
  // solves, and the one kept is the one of least recorded cost (which one that is depends on the
  // machine: that is the point). Which solver solves no step changes the answer beyond the
  // tolerance: every solve reaches 1e-10, so the displacements agree with CHOLMOD's far inside
  // 1e-6 of the largest (as in AProjectedStartIsRecordedAndSolvesTheSameSteps).
  TempDir dir;
  std::vector<nlohmann::json> records;
  for (const char* solver : {"auto", "cholmod"}) {
    records.push_back(run_record(dir, dynamic_cube(solver)));
    ASSERT_FALSE(records.back().is_null()) << solver;
  }
  const nlohmann::json& choice = records[0]["solver_choice"];
  ASSERT_EQ(choice["candidates"].size(), 2u);
  EXPECT_EQ(choice["candidates"][0]["name"], "mgpcg");
  EXPECT_EQ(choice["candidates"][1]["name"], "jacobi-pcg");
  const int trial = choice["decided_after"];
  EXPECT_GE(trial, 2);  // a warm-up solve and one measured
  EXPECT_LE(trial, choice["trial_solves"].get<int>());
  std::string cheapest;
  double least = 0;
  for (const auto& c : choice["candidates"]) {
    ASSERT_EQ(c["trial_ms"].size(), static_cast<std::size_t>(trial)) << c["name"];
    ASSERT_EQ(c["iterations"].size(), static_cast<std::size_t>(trial)) << c["name"];
    double cost = c["trial_ms"][1];
    for (int s = 1; s < trial; ++s) cost = std::min(cost, c["trial_ms"][s].get<double>());
    EXPECT_EQ(c["cost_ms"].get<double>(), cost) << c["name"];
    if (cheapest.empty() || cost < least) cheapest = c["name"], least = cost;
  }
  EXPECT_EQ(choice["chosen"], cheapest);
  EXPECT_EQ(records[0]["analysis"]["solver"], "auto: " + cheapest);
  EXPECT_EQ(records[0].contains("multigrid"), cheapest == "mgpcg");  // the kept solver's record
  // Multigrid's preconditioner takes fewer iterations than Jacobi's on every trial system.
  for (int s = 0; s < trial; ++s)
    EXPECT_LT(choice["candidates"][0]["iterations"][s].get<int>(),
              choice["candidates"][1]["iterations"][s].get<int>())
        << "trial solve " << s;
  EXPECT_LT(displacement_difference(records[0]["displacement"], records[1]["displacement"]), 1e-6);
}

TEST(CliRun, BadCoarseMeshIsBadInput) {
  // A coarse level away from the body, a degenerate one, and one that covers too little: exit 2,
  // a message naming the fault, no output.
  struct Case {
    const char* name;
    std::string msh;
    const char* fragment;
  };
  const std::vector<std::array<int, 4>> one_tet{{1, 2, 3, 4}};
  std::vector<std::array<double, 3>> short_box;
  for (int v = 0; v < 8; ++v)
    short_box.push_back({v & 1 ? 0.55 : 0.0, v & 2 ? 1.0 : 0.0, v & 4 ? 1.0 : 0.0});
  const std::vector<std::array<int, 4>> kuhn_cube{{1, 2, 4, 8}, {1, 2, 6, 8}, {1, 3, 4, 8},
                                                  {1, 3, 7, 8}, {1, 5, 6, 8}, {1, 5, 7, 8}};
  const Case cases[] = {
      {"away", msh_v2({{{10, 0, 0}}, {{11, 0, 0}}, {{10, 1, 0}}, {{10, 0, 1}}}, one_tet),
       "does not overlap"},
      {"flat", msh_v2({{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{1, 1, 0}}}, one_tet), "degenerate"},
      {"corner", msh_v2({{{0, 0, 0}}, {{0.3, 0, 0}}, {{0, 0.3, 0}}, {{0, 0, 0.3}}}, one_tet),
       "lie outside it"},
      // [0, 0.55] x [0, 1]^2 in 6 tets: the fine vertices at x = 1 are 0.45 from it, more than
      // a quarter of the cube's diagonal.
      {"short", msh_v2(short_box, kuhn_cube), "does not cover"},
  };
  for (const Case& c : cases) {
    TempDir dir;
    write_text(dir / "coarse.msh", c.msh);
    write_text(dir / "cube.json", multigrid_cube({{"file", "coarse.msh"}}).dump());
    const auto out = dir / "r.json";
    const auto r =
        run_cli("run '" + (dir / "cube.json").string() + "' --out '" + out.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.fragment), std::string::npos) << c.name << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
  }
}

TEST(CliRun, AlternateRunsComparesTwoConfigurations) {
  // bench/alternate_runs.py, the tool issue 36's timing targets are measured with: two
  // configurations alternated, medians, ratios, and whether they computed the same thing.
  TempDir dir;
  const std::string bar = R"({
    "mesh": {"box": [1, 0.1, 0.1], "cells": [12, 2, 2]},
    "material": {"young": 5e6, "poisson": 0.3, "density": 1000},
    "fixed": [{"box": [[0, 0, 0], [0, 0.1, 0.1]]}],
    "gravity": [0, 0, -9.81],
    "analysis": {"type": "dynamic", "solver": "mgpcg", "levels": 2, "dt": 0.01, "steps": 4,
                 "tolerance": TOL}})";
  const auto with_tolerance = [&](const std::string& tolerance) {
    std::string scene = bar;
    return scene.replace(scene.find("TOL"), 3, tolerance);
  };
  write_text(dir / "a.json", with_tolerance("1e-4"));
  write_text(dir / "b.json", with_tolerance("1e-10"));
  const auto compare = [&](const std::string& candidate_scene, const std::string& out) {
    const std::string command =
        "python3 '" + (test::source_dir() / "bench" / "alternate_runs.py").string() +
        "' --runs 2 --threads 1 --target step=1e9 --target solve=1e-9 --baseline '" + COROFEM_CLI +
        "' --candidate '" + COROFEM_CLI + ":" + (dir / candidate_scene).string() + "' --out '" +
        (dir / out).string() + "' '" + (dir / "a.json").string() + "' 2> '" +
        (dir / "err").string() + "'";
    return std::system(command.c_str());
  };
  ASSERT_EQ(compare("a.json", "same.json"), 0) << test::read_text(dir / "err");
  ASSERT_EQ(compare("b.json", "other.json"), 0) << test::read_text(dir / "err");
  // Written whole through a rename, and readable by all as every other result file.
  EXPECT_NE(std::filesystem::status(dir / "same.json").permissions() &
                std::filesystem::perms::others_read,
            std::filesystem::perms::none);
  const auto same = nlohmann::json::parse(test::read_text(dir / "same.json"))["comparisons"][0];
  const auto other = nlohmann::json::parse(test::read_text(dir / "other.json"))["comparisons"][0];
  // One binary on one scene gives the same bits (a run is deterministic); a tolerance 1e6 times
  // tighter takes more CG iterations and moves the displacements far more than 1e-12 of them.
  EXPECT_TRUE(same["same_result"].get<bool>());
  EXPECT_FALSE(other["same_result"].get<bool>());
  for (const auto& c : {same, other}) {
    for (const char* name : {"baseline", "candidate"}) {
      const auto& runs = c[name]["ms_per_step_runs"];
      ASSERT_EQ(runs["step"].size(), 2u);
      const auto& ms = c[name]["ms_per_step"];
      // The solve is a phase of the step, and the median of two runs lies between them.
      EXPECT_GT(ms["solve"].get<double>(), 0);
      EXPECT_LE(ms["solve"].get<double>(), ms["step"].get<double>());
      EXPECT_GE(ms["step"].get<double>(),
                std::min(runs["step"][0].get<double>(), runs["step"][1].get<double>()));
      EXPECT_TRUE(c[name]["context"].contains("commit"));
    }
    const double ratio = c["candidate_over_baseline"]["step"].get<double>();
    EXPECT_NEAR(ratio,
                c["candidate"]["ms_per_step"]["step"].get<double>() /
                    c["baseline"]["ms_per_step"]["step"].get<double>(),
                1e-12 * ratio);
    ASSERT_EQ(c["targets"].size(), 2u);
    EXPECT_TRUE(c["targets"][0]["met"].get<bool>());   // step ratio <= 1e9
    EXPECT_FALSE(c["targets"][1]["met"].get<bool>());  // solve ratio <= 1e-9
  }
  // A run that fails stops the tool with its message, and nothing is written.
  write_text(dir / "b.json", "{");
  EXPECT_NE(compare("b.json", "failed.json"), 0);
  EXPECT_NE(test::read_text(dir / "err").find("b.json"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "failed.json"));
}

TEST(CliHelp, ToolAndCommandHelp) {
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  const auto r = run_cli("run --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--out"), std::string::npos);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
}

}  // namespace
}  // namespace corofem
