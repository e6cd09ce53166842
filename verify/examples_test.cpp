// The example gallery (bench/scenes/) runs, so that the scenes users copy never rot: each scene
// with its step counts cut short, from a copy beside a `models` link to the models folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "solver/petsc_solver.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Example {
  const char* file;
  bool needs_models = false;
  bool needs_petsc = false;
};

const Example kExamples[] = {
    {"cantilever.json"},
    {"quadruped_static_newton.json"},
    {"column_static_newton_mgpcg.json"},
    {"block_squash_stability.json"},
    {"box_petsc_gamg_mpi.json", false, true},
    {"bar_static_newton_mpi.json", false, true},
    {"bunny_dynamic.json", true},
    {"dragon_given_levels.json", true},
    {"horse_bare_stl.json", true},
};

fs::path gallery() {
  return test::source_dir() / "bench" / "scenes";
}

TEST(Examples, GalleryIsTheListTested) {
  std::set<std::string> files, listed;
  for (const auto& entry : fs::directory_iterator(gallery()))
    if (entry.path().extension() == ".json") files.insert(entry.path().filename().string());
  for (const Example& e : kExamples) listed.insert(e.file);
  EXPECT_EQ(files, listed) << "bench/scenes/ and kExamples must list the same scenes";
}

class EachExample : public ::testing::TestWithParam<Example> {};

/// Runs the example from a copy with at most 3 dynamic steps (behind `launcher` if given) and
/// checks that it converged and wrote its outputs.
void run_example(const Example& example, const std::string& launcher = "") {
  test::TempDir dir;
  json scene = json::parse(test::read_text(gallery() / example.file));
  json& analysis = scene["analysis"];
  if (analysis.value("type", "static") == "dynamic")
    analysis["steps"] = std::min(analysis["steps"].get<int>(), 3);
  test::write_text(dir / example.file, scene.dump());
  if (example.needs_models) fs::create_directory_symlink(test::models_dir(), dir / "models");
  const test::CliResult r = test::run_cli(
      "run '" + (dir / example.file).string() + "' --out '" + (dir / "result.json").string() + "'",
      launcher);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json result = json::parse(test::read_text(dir / "result.json"));
  EXPECT_TRUE(result["converged"].get<bool>()) << result.dump();
  if (scene.contains("output") && scene["output"].contains("vtu")) {
    EXPECT_TRUE(fs::exists(dir / scene["output"]["vtu"].get<std::string>()));
  }
}

TEST_P(EachExample, RunsAndConverges) {
  const Example& e = GetParam();
  if (e.needs_models && test::models_dir().empty())
    GTEST_SKIP() << e.file << " reads the models folder (set COROFEM_MODELS)";
  if (e.needs_petsc && !have_petsc())
    GTEST_SKIP() << e.file << " needs PETSc, which this build does not have";
  run_example(e);
  // The MPI example as its README line runs it: two ranks (ci/setup installs mpirun with PETSc).
  if (e.needs_petsc) run_example(e, test::mpirun_two_ranks());
}

INSTANTIATE_TEST_SUITE_P(Gallery, EachExample, ::testing::ValuesIn(kExamples),
                         [](const auto& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace corofem
