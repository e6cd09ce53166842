// Every numeric key of the scene format against hostile numbers: beyond a double (+-1e400), huge
// but finite (+-1e308), denormal, -0, and both ends of the key's documented range (README, "Scene
// limits"). Each is refused with an InputError naming the key, or, where the value is legal,
// accepted; never an internal error. A sample goes through the CLI for the exit status 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "scene/memory_estimate.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::TempDir;
using test::write_text;

/// A valid scene in which every numeric key of the format appears (parsed, not run).
nlohmann::json full_scene() {
  return nlohmann::json::parse(R"({
    "mesh": {"box": [1, 0.2, 0.2], "cells": [4, 1, 1]},
    "material": {"young": 1e5, "poisson": 0.3, "density": 1000,
                 "regions": [{"box": [[0, 0, 0], [0.5, 0.2, 0.2]], "young": 2e5, "poisson": 0.25, "density": 900}]},
    "fixed": [{"box": [[0, 0, 0], [0, 0.2, 0.2]]}],
    "gravity": [0, 0, -9.81],
    "forces": [{"box": [[1, 0, 0], [1, 0.2, 0.2]], "total": [0, 0, -1], "ramp_steps": 2, "release_step": 0}],
    "moves": [{"box": [[1, 0, 0], [1, 0.2, 0.2]], "translate": [0, 0, 0.01],
               "rotate": {"axis": [1, 0, 0], "center": [1, 0.1, 0.1], "degrees": 10},
               "ramp_steps": 2, "release_step": 0}],
    "analysis": {"type": "dynamic", "solver": "mgpcg", "levels": 2, "vcycles": 0, "smoothing": 1,
                 "coarsest_refactor": 0.03, "dt": 0.01, "steps": 3, "load_steps": 1,
                 "tolerance": 1e-8, "max_iterations": 100,
                 "rayleigh": {"alpha": 0.1, "beta": 0.001},
                 "rotation_params": {"newton_tolerance": 1e-9, "newton_max_iterations": 20,
                                     "mueller_iterations": 10, "mueller_tolerance": 1e-9,
                                     "smoothing_passes": 1}}})");
}

struct NumericKey {
  std::string pointer;                         ///< JSON pointer of the value replaced
  std::string path;                            ///< the key path the error must name
  std::vector<std::string> accepted, refused;  ///< the range's ends and just beyond them
};

const std::vector<NumericKey>& numeric_keys() {
  static const std::vector<NumericKey> keys = {
      {"/mesh/box/0", "mesh.box", {"1e-9", "1e9"}, {"0", "-1", "9e-10", "1.1e9"}},
      {"/mesh/cells/0", "mesh.cells", {"1", "1000"}, {"0", "-1", "100001", "1.5"}},
      {"/mesh/size", "mesh.size", {"1e-9", "1e9"}, {"0", "-1", "1.1e9"}},  // on a surface mesh
      {"/material/young", "material.young", {"1e-9", "1e15"}, {"0", "-1", "1.1e15"}},
      {"/material/poisson", "material.poisson", {"-0.99", "0", "0.49"}, {"-1", "0.5"}},
      {"/material/density", "material.density", {"1e-9", "1e9"}, {"0", "-1", "1.1e9"}},
      {"/material/regions/0/young", "material.regions[0].young", {"1e-9", "1e15"}, {"0", "1.1e15"}},
      {"/material/regions/0/poisson",
       "material.regions[0].poisson",
       {"-0.99", "0.49"},
       {"-1", "0.5"}},
      {"/material/regions/0/density",
       "material.regions[0].density",
       {"1e-9", "1e9"},
       {"0", "1.1e9"}},
      {"/material/regions/0/box/1/0", "material.regions[0].box", {"1e9"}, {"1.1e9"}},
      {"/fixed/0/box/0/0", "fixed[0].box", {"-1e9"}, {"-1.1e9"}},
      {"/gravity/2", "gravity", {"-1e9", "1e9"}, {"-1.1e9", "1.1e9"}},
      {"/forces/0/box/1/1", "forces[0].box", {"1e9"}, {"1.1e9"}},
      {"/forces/0/total/2", "forces[0].total", {"-1e18", "1e18"}, {"1.1e18"}},
      {"/forces/0/ramp_steps", "forces[0].ramp_steps", {"0", "10000000"}, {"-1", "10000001"}},
      {"/forces/0/release_step", "forces[0].release_step", {"0", "10000000"}, {"-1", "10000001"}},
      {"/moves/0/box/0/2", "moves[0].box", {"-1e9"}, {"-1.1e9"}},
      {"/moves/0/translate/0", "moves[0].translate", {"-1e9", "1e9"}, {"1.1e9"}},
      {"/moves/0/rotate/axis/0", "moves[0].rotate.axis", {"1e9", "-1e9"}, {"1.1e9"}},
      {"/moves/0/rotate/center/1", "moves[0].rotate.center", {"-1e9", "1e9"}, {"1.1e9"}},
      {"/moves/0/rotate/degrees", "moves[0].rotate.degrees", {"-36000", "36000"}, {"36001"}},
      {"/moves/0/ramp_steps", "moves[0].ramp_steps", {"0", "10000000"}, {"-1", "10000001"}},
      {"/moves/0/release_step", "moves[0].release_step", {"0", "10000000"}, {"-1", "10000001"}},
      {"/analysis/levels", "analysis.levels", {"1", "16"}, {"0", "17"}},
      {"/analysis/vcycles", "analysis.vcycles", {"0", "1000"}, {"-1", "1001"}},
      {"/analysis/smoothing", "analysis.smoothing", {"1", "100"}, {"0", "101"}},
      {"/analysis/coarsest_refactor", "analysis.coarsest_refactor", {"0", "1"}, {"-0.01", "1.1"}},
      {"/analysis/dt", "analysis.dt", {"1e-9", "1e6"}, {"0", "9e-10", "1.1e6"}},
      {"/analysis/steps", "analysis.steps", {"1", "10000000"}, {"0", "10000001"}},
      {"/analysis/load_steps", "analysis.load_steps", {"1", "100000"}, {"0", "100001"}},
      {"/analysis/tolerance", "analysis.tolerance", {"1e-15", "0.5"}, {"0", "9e-16", "0.6"}},
      {"/analysis/max_iterations", "analysis.max_iterations", {"1", "100000"}, {"0", "100001"}},
      {"/analysis/rayleigh/alpha", "analysis.rayleigh.alpha", {"0", "1e9"}, {"-1e-9", "1.1e9"}},
      {"/analysis/rayleigh/beta", "analysis.rayleigh.beta", {"0", "1e9"}, {"-1e-9", "1.1e9"}},
      {"/analysis/rotation_params/newton_tolerance",
       "analysis.rotation_params.newton_tolerance",
       {"1e-15", "0.5"},
       {"0", "0.6"}},
      {"/analysis/rotation_params/newton_max_iterations",
       "analysis.rotation_params.newton_max_iterations",
       {"1", "100"},
       {"0", "101"}},
      {"/analysis/rotation_params/mueller_iterations",
       "analysis.rotation_params.mueller_iterations",
       {"1", "200"},
       {"0", "201"}},
      {"/analysis/rotation_params/mueller_tolerance",
       "analysis.rotation_params.mueller_tolerance",
       {"1e-15", "0.5"},
       {"0", "0.6"}},
      {"/analysis/rotation_params/smoothing_passes",
       "analysis.rotation_params.smoothing_passes",
       {"0", "100"},
       {"-1", "101"}},
  };
  return keys;
}

/// The scene with the value at `pointer` replaced by the raw JSON text `value`, written to `file`.
void write_scene_with(const std::filesystem::path& file, const std::string& pointer,
                      const std::string& value) {
  nlohmann::json scene = full_scene();
  if (pointer == "/mesh/size") scene["mesh"] = {{"surface", "a.stl"}, {"size", 0.1}};
  const std::string marker = "@@value@@";
  scene[nlohmann::json::json_pointer(pointer)] = marker;
  std::string text = scene.dump();
  text.replace(text.find("\"" + marker + "\""), marker.size() + 2, value);
  write_text(file, text);
}

/// The last object key of a JSON pointer ("/gravity/2" -> "gravity"): what a parser error names.
std::string last_key(const std::string& pointer) {
  std::string key;
  std::size_t start = 1;
  while (start <= pointer.size()) {
    const std::size_t end = std::min(pointer.find('/', start), pointer.size());
    const std::string token = pointer.substr(start, end - start);
    if (token.find_first_not_of("0123456789") != std::string::npos) key = token;
    start = end + 1;
  }
  return key;
}

enum class Expect { Refused, Accepted, Either };

void check(const TempDir& dir, const NumericKey& key, const std::string& value, Expect expect,
           const std::string& names) {
  SCOPED_TRACE(key.pointer + " = " + value);
  const auto file = dir / "scene.json";
  write_scene_with(file, key.pointer, value);
  try {
    load_scene(file);
    EXPECT_NE(expect, Expect::Refused) << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(expect, Expect::Accepted) << e.what();
    EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
  }
}

TEST(SceneNumberLimits, EveryNumericKeyRefusesHostileNumbersNamingTheKey) {
  TempDir dir;
  write_scene_with(dir / "scene.json", "/analysis/dt", "0.01");
  ASSERT_NO_THROW(load_scene(dir / "scene.json"));  // the base scene itself is valid
  for (const NumericKey& key : numeric_keys()) {
    for (const char* beyond_double : {"1e400", "-1e400"})
      check(dir, key, beyond_double, Expect::Refused, "key '" + last_key(key.pointer) + "'");
    for (const char* hostile : {"1e308", "-1e308", "4.9e-324", "-2.5e-310"})
      check(dir, key, hostile, Expect::Refused, key.path);
    check(dir, key, "-0", Expect::Either, key.path);
    check(dir, key, "-0.0", Expect::Either, key.path);
    for (const std::string& v : key.accepted) check(dir, key, v, Expect::Accepted, key.path);
    for (const std::string& v : key.refused) check(dir, key, v, Expect::Refused, key.path);
  }
}

TEST(SceneNumberLimits, BoxTooLargeForThisMachineIsRefusedBeforeAllocating) {
  TempDir dir;
  write_scene_with(dir / "scene.json", "/mesh/cells", "[100000, 100000, 100000]");
  try {
    load_scene(dir / "scene.json");
    ADD_FAILURE() << "accepted 6e15 tets";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mesh.cells would give about 6e+15 tets"), std::string::npos) << what;
    EXPECT_NE(what.find("this machine has"), std::string::npos) << what;
  }
}

/// The memory check's estimate bounds what a run takes: the peak RSS of a dynamic box of 48k tets
/// run by the CLI with each of corofem's own solvers stays below run_bytes (measured 5-10% below
/// at 197k tets); and the check depends on the scene's solver: a box of 4.4 million tets is refused
/// for CHOLMOD (fill: about 82 GB) but let through for MG-PCG (about 6.6 GB; with static Newton's
/// GMRES 10.6 GB) on this machine.
TEST(SceneNumberLimits, MemoryEstimateBoundsARunAndDependsOnTheSolver) {
#ifdef COROFEM_ASAN_BUILD
  GTEST_SKIP() << "ASan's shadow memory and quarantine change every RSS";
#endif
  TempDir dir;
  for (const char* solver : {"cholmod", "mgpcg", "jacobi-pcg"}) {
    test::write_text(dir / "box.json",
                     std::string(R"({"mesh": {"box": [1, 1, 1], "cells": [20, 20, 20]},
      "material": {"young": 1e5, "poisson": 0.3, "density": 1000},
      "fixed": [{"box": [[0, 0, 0], [1, 1, 0.0001]]}], "gravity": [0, 0, -9.81],
      "analysis": {"type": "dynamic", "dt": 0.01, "steps": 3, "tolerance": 1e-4, "solver": ")") +
                         solver + R"("}})");
    const auto r = test::run_cli("run '" + (dir / "box.json").string() + "' --out '" +
                                 (dir / "r.json").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << solver << ": " << r.err;
    const double peak =
        1024.0 *
        nlohmann::json::parse(test::read_text(dir / "r.json"))["peak_rss_kb"].get<double>();
    const double estimate = run_bytes(solver_named(solver), 48000);
    EXPECT_LT(peak, estimate) << solver;
    EXPECT_GT(peak, 0.4 * estimate) << solver << ": the estimate is far from the run";
  }
  const double have = physical_memory_bytes();
  const double tets = 6.0 * 90 * 90 * 90;  // 4.4 million
  if (have < 2 * run_bytes(SolverKind::Mgpcg, tets, 1, NewtonTangent::ByGmres) ||
      have > run_bytes(SolverKind::Cholmod, tets))
    GTEST_SKIP() << "this machine's " << have / 1e9 << " GB do not separate the two solvers";
  for (const char* solver : {"cholmod", "mgpcg"}) {
    write_scene_with(dir / "scene.json", "/mesh/cells", "[90, 90, 90]");
    nlohmann::json scene = nlohmann::json::parse(test::read_text(dir / "scene.json"));
    scene["analysis"]["solver"] = solver;
    bool refused = false;
    try {
      EXPECT_EQ(parse_scene(scene, dir.path(), "scene.json").mesh.estimated_tets, tets);
    } catch (const InputError& e) {
      refused = true;
      EXPECT_NE(std::string(e.what()).find(std::string(solver) + ": "), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(refused, std::string(solver) == "cholmod") << solver;
  }
  // Static corotated Newton: on `cholmod` it factors its tangent and is refused, naming the
  // factorizations; on the multigrid GMRES takes the tangent, preconditioned by it, and the scene
  // gets past the memory check with the multigrid's and GMRES's bytes per tet (its next error is
  // the scene's moves, which a static analysis refuses).
  for (const char* solver : {"cholmod", "mgpcg"}) {
    write_scene_with(dir / "scene.json", "/mesh/cells", "[90, 90, 90]");
    nlohmann::json newton = nlohmann::json::parse(test::read_text(dir / "scene.json"));
    newton["analysis"]["type"] = "static";
    newton["analysis"]["integrator"] = "newton";
    newton["analysis"]["solver"] = solver;
    try {
      parse_scene(newton, dir.path(), "scene.json");
      ADD_FAILURE() << solver << ": the scene's moves were let through in a static analysis";
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (std::string(solver) == "cholmod")
        EXPECT_NE(what.find("Newton's sparse factorizations"), std::string::npos) << what;
      else
        EXPECT_NE(what.find("moves need a dynamic analysis"), std::string::npos) << what;
    }
  }
}

TEST(SceneNumberLimits, CliExitsTwoNamingTheKey) {
  TempDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {"/material/young", "1e308"}, {"/analysis/dt", "4.9e-324"}, {"/gravity/0", "-1e400"}};
  for (const auto& [pointer, value] : cases) {
    write_scene_with(dir / "scene.json", pointer, value);
    const auto out = dir / "r.json";
    const auto r =
        test::run_cli("run '" + (dir / "scene.json").string() + "' --out '" + out.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << pointer << " = " << value << ": " << r.err;
    EXPECT_NE(r.err.find(last_key(pointer)), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace corofem
