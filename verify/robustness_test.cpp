// Faults during runs: NaN/inf stops with NumericalFault (exit 1) naming the step and element;
// inverted elements are counted, not fatal; a full disk is a clear error with no partial file;
// SIGINT leaves no partial file; a 10,000-step run keeps constant memory.
#include <gtest/gtest.h>

#include <csignal>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/run_scene.hpp"
#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "fem/corotated_system.hpp"
#include "fem/fe_problem.hpp"
#include "integrate/implicit_euler.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::run_cli;
using test::TempDir;
using test::write_text;

std::string bar_scene(const std::string& gravity, const std::string& analysis) {
  return R"({"mesh": {"box": [1, 0.1, 0.1], "cells": [10, 1, 1]},
    "material": {"young": 1e5, "poisson": 0.3, "density": 1000},
    "fixed": [{"box": [[0, 0, 0], [0, 0.1, 0.1]]}], "gravity": )" +
         gravity + R"(, "analysis": )" + analysis + "}";
}

TEST(Robustness, OverflowingLoadStopsNamingStepAndElement) {
  // rho g overflows to inf: the first solve produces inf/NaN displacements. The scene format
  // refuses gravity beyond 1e9 (exit 2), so the load is set past the parser, as a bug would.
  Scene scene = parse_scene(nlohmann::json::parse(bar_scene(
                                "[0, 0, -9.81]", R"({"type": "dynamic", "dt": 0.01, "steps": 5})")),
                            ".", "bar.json");
  scene.gravity = Vec3(0, 0, -1e308);
  try {
    run_scene(scene);
    ADD_FAILURE() << "no NumericalFault";
  } catch (const NumericalFault& e) {  // the CLI maps it to exit 1
    const std::string what = e.what();
    EXPECT_NE(what.find("non-finite"), std::string::npos) << what;
    EXPECT_NE(what.find("step"), std::string::npos) << what;
    EXPECT_NE(what.find("element"), std::string::npos) << what;
  }
}

TEST(Robustness, FiniteForcesWhoseNormOverflowsAreAFault) {
  // Entries of 1e200 are finite, their squares are not: a residual or norm of them is inf, so
  // the check must not let them through as a run that converged with a NaN residual.
  TetMesh mesh = make_box_mesh({1.0, 0.1, 0.1}, {4, 1, 1});
  const std::vector<Material> materials(mesh.tets.size(), Material{1e5, 0.3, 1000});
  const FeProblem problem = make_fe_problem(std::move(mesh), materials);
  Eigen::VectorXd f = Eigen::VectorXd::Ones(problem.num_dofs());
  EXPECT_NO_THROW(check_finite(problem, f, "force", "step 1"));
  const int node = problem.mesh.tets[3][2];
  f[3 * node + 1] = 1e200;
  try {
    check_finite(problem, f, "force", "step 1");
    ADD_FAILURE() << "no NumericalFault";
  } catch (const NumericalFault& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("non-finite force norm at step 1"), std::string::npos) << what;
    EXPECT_NE(what.find("(node " + std::to_string(problem.mesh.node_tags[node]) + ")"),
              std::string::npos)
        << what;
  }
}

TEST(Robustness, InvertedElementsAreCountedNotFatal) {
  TempDir dir;
  // A soft block squashed by a force larger than it can bear in one implicit step.
  write_text(dir / "s.json", R"({"mesh": {"box": [1, 1, 1], "cells": [2, 2, 2]},
    "material": {"young": 1e3, "poisson": 0.3, "density": 100},
    "fixed": [{"box": [[0, 0, 0], [1, 1, 0]]}],
    "forces": [{"box": [[0, 0, 1], [1, 1, 1]], "total": [0, 0, -5e4]}],
    "analysis": {"type": "dynamic", "rotation": "polar-fixed", "dt": 0.05, "steps": 20}})");
  const auto r =
      run_cli("run '" + (dir / "s.json").string() + "' --out '" + (dir / "r.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_text(dir / "r.json"));
  EXPECT_GT(j["inverted_max"].get<int>(), 0);
}

TEST(Robustness, FullDiskIsAClearErrorWithoutPartialFile) {
  TempDir dir;
  write_text(dir / "s.json", bar_scene("[0, 0, -9.81]", R"({"type": "static"})"));
  // A 1-block file size limit with SIGXFSZ ignored: writes fail as on a full disk.
  const std::string command = "bash -c \"trap '' XFSZ; ulimit -f 1; '" + std::string(COROFEM_CLI) +
                              "' run '" + (dir / "s.json").string() + "' --out '" +
                              (dir / "r.json").string() + "'\"";
  const int status = std::system((command + " 2> '" + (dir / "err").string() + "'").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(test::read_text(dir / "err").find("disk full"), std::string::npos)
      << test::read_text(dir / "err");
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find("r.json"), std::string::npos) << entry.path();
}

TEST(Robustness, InterruptLeavesNoPartialFile) {
  TempDir dir;
  write_text(dir / "s.json",
             bar_scene("[0, 0, -9.81]", R"({"type": "dynamic", "dt": 0.001, "steps": 10000000})"));
  write_text(dir / "interrupt.sh",
             "'" + std::string(COROFEM_CLI) + "' run '" + (dir / "s.json").string() + "' --out '" +
                 (dir / "r.json").string() +
                 "' 2>/dev/null &\npid=$!\nsleep 1\nkill -INT $pid\nwait $pid\n");
  const int status = std::system(("bash '" + (dir / "interrupt.sh").string() + "'").c_str());
  EXPECT_NE(WEXITSTATUS(status), 0);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find("r.json"), std::string::npos) << entry.path();
}

TEST(Robustness, TenThousandStepsKeepConstantMemory) {
#ifdef COROFEM_ASAN_BUILD
  GTEST_SKIP() << "ASan's quarantine keeps up to 256 MB of freed memory resident, so RSS says "
                  "nothing here; in this build LeakSanitizer checks for leaks at exit instead";
#endif
  TetMesh mesh = make_box_mesh({1, 0.2, 0.2}, {5, 1, 1});
  std::vector<Material> m(mesh.tets.size(), Material{1e5, 0.3, 1000});
  FeProblem p = make_fe_problem(std::move(mesh), std::move(m));
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v].x() == 0) p.dirichlet.fix_vertex(v);
  p.external_force.setConstant(-1.0);
  auto rotation = make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh);
  auto solver = make_cholmod_solver();
  long at_1000 = 0, at_10000 = 0;
  solve_dynamic(p, *rotation, *solver, {true, 0.01, 10000, 1.0, 0.0}, [&](const StepState& s) {
    if (s.step == 1000) at_1000 = current_rss_kb();
    if (s.step == 10000) at_10000 = current_rss_kb();
  });
  std::cout << "[ long run ] RSS at step 1000: " << at_1000 << " kB, at step 10000: " << at_10000
            << " kB, peak " << peak_rss_kb() << " kB\n";
  // Both readings must have been taken: a run that stopped early, or an RSS that could not be
  // read (current_rss_kb() returns 0), measures nothing.
  ASSERT_GT(at_1000, 0) << "step 1000 not reached, or RSS unreadable";
  ASSERT_GT(at_10000, 0) << "step 10000 not reached, or RSS unreadable";
  // A leak of even 100 bytes per step would add ~900 kB over the 9000 steps.
  EXPECT_LT(at_10000 - at_1000, 256);
}

}  // namespace
}  // namespace corofem
