// The CLI end to end: a run writes the documented record; every bad input exits 2 with a message
// naming the file, key or element, and leaves no output file behind.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

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

TEST(CliRun, WritesTheDocumentedRecord) {
  TempDir dir;
  write_text(dir / "bar.json", kScene);
  const auto r = run_cli("run '" + (dir / "bar.json").string() + "' --out '" +
                         (dir / "result.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("converged"), std::string::npos);  // progress on stderr
  const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
  for (const char* key : {"node_tags", "rest", "displacement", "converged", "iterations", "residual",
                          "timings_ms", "scene", "context", "element_tags", "rotations"})
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
  // Each quaternion is unit, and rotates the element's rest edges onto the deformed ones to
  // within the element's strain (small here): check one element at the tip.
  for (const auto& q : j["rotations"]) {
    Eigen::Quaterniond quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
    EXPECT_NEAR(quat.norm(), 1.0, 1e-12);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "bar.vtu"));
}

struct BadRun {
  const char* name;
  const char* scene;      // scene text; empty: no scene file
  const char* fragment;   // in stderr
};

void PrintTo(const BadRun& c, std::ostream* os) { *os << c.name; }

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
    {"UnknownKey", R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3}, "colour": 1})",
     "colour is not a known key"},
    {"MissingMeshFile", R"({"mesh": {"file": "nope.msh"}, "material": {"young": 1, "poisson": 0.3}})",
     "nope.msh' does not exist"},
    {"FixedSelectsNothing", R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3},
       "fixed": [{"box": [[5,5,5],[6,6,6]]}]})", "fixed[0].box selects no vertex"},
    {"RigidMotionFree", R"({"mesh": {"box": [1,1,1], "cells": [2,2,2]}, "material": {"young": 1, "poisson": 0.3},
       "fixed": [{"box": [[0,0,0],[0,0,1]]}]})", "leaves rigid motions free"},
    {"NoSupportsStatic", R"({"mesh": {"box": [1,1,1], "cells": [1,1,1]}, "material": {"young": 1, "poisson": 0.3}})",
     "leaves rigid motions free"},
};

INSTANTIATE_TEST_SUITE_P(Cases, CliBadInput, ::testing::ValuesIn(kBadRuns),
                         [](const auto& info) { return std::string(info.param.name); });

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
  const auto j = nlohmann::json::parse(test::read_text(dir / "result.json"));
  EXPECT_FALSE(j["converged"].get<bool>());
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
