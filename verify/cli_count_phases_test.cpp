// `corofem run --count-phases` and bench/count_phases.py end to end: a counted run has every phase
// and solver part, parents hold their parts, the same counts twice, the numerics untouched; perf
// falls back with a reason where the machine has no counters; ci/count-gate passes against its
// own counts and fails, naming the phase, against a baseline that cost less; ci/bench-gate times a
// tiny suite alternated and compares it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace corofem {
namespace {

using json = nlohmann::json;
using test::run_cli;
using test::run_command;
using test::TempDir;

std::string quoted(const std::filesystem::path& p) {
  return "'" + p.string() + "'";
}

/// The words joined by spaces: a shell command line.
std::string words(std::initializer_list<std::string> parts) {
  std::string line;
  for (const std::string& part : parts) line.append(line.empty() ? "" : " ").append(part);
  return line;
}

std::filesystem::path gate_scene() {
  return test::source_dir() / "bench" / "gate" / "cantilever_small.json";
}

/// The folder of the corofem binary the gates test, for the scripts' --bin.
std::filesystem::path bin_dir() {
  return std::filesystem::path(COROFEM_CLI).parent_path();
}

bool can_count_under_valgrind() {
#ifdef COROFEM_ASAN_BUILD
  return false;  // valgrind cannot run a sanitized binary
#else
  return std::system("valgrind --version > /dev/null 2>&1") == 0;
#endif
}

TEST(CliCountPhases, PerfCountsOrSaysWhyAndTheRunGoesOn) {
  TempDir dir;
  const auto r = run_cli("run " + quoted(gate_scene()) + " --out " + quoted(dir / "r.json") +
                         " --threads 1 --count-phases perf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json record = json::parse(test::read_text(dir / "r.json"));
  const json& counts = record.at("phase_counts");
  if (counts["source"].is_null()) {  // a VM without a virtual PMU: the record says why
    EXPECT_EQ(counts["asked"], "perf");
    EXPECT_NE(counts["unavailable"].get<std::string>().find("perf_event_open"), std::string::npos);
    EXPECT_NE(r.err.find("phases not counted"), std::string::npos) << r.err;
  } else {
    for (const char* phase : {"rotate", "assemble", "update", "solve"})
      EXPECT_GT(counts["sections"][phase]["instructions"].get<double>(), 0) << phase;
  }
  EXPECT_TRUE(record.contains("step_samples_ms"));  // the timings are still measured
}

TEST(CliCountPhases, AnUnknownSourceIsBadInput) {
  TempDir dir;
  const auto r = run_cli("run " + quoted(gate_scene()) + " --out " + quoted(dir / "r.json") +
                         " --count-phases sideways");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--count-phases: 'sideways'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
}

TEST(CliCountPhases, CallgrindCountsEveryPartTheSameTwiceAndLeavesTheNumericsAlone) {
  if (!can_count_under_valgrind()) GTEST_SKIP() << "no valgrind here, or a sanitized build";
  TempDir dir;
  for (const char* side : {"a", "b"}) {
    const auto r = run_command(words(
        {"python3", quoted(test::source_dir() / "bench/count_phases.py"), quoted(gate_scene()),
         "--keep-fields --bin", quoted(bin_dir()), "--out", quoted(dir / side)}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const json a = json::parse(test::read_text(dir / "a" / "cantilever_small.json"));
  const json b = json::parse(test::read_text(dir / "b" / "cantilever_small.json"));
  const json& sections = a["phase_counts"]["sections"];
  // The same binary, scene and layout: the same counts, to the instruction and the miss.
  EXPECT_EQ(sections, b["phase_counts"]["sections"]);
  EXPECT_EQ(a["phase_counts"]["source"], "callgrind");
  for (const char* part : {"rotate", "assemble", "forces", "system", "checks", "update",
                           "update/galerkin", "update/smoothers", "update/coarsest", "solve",
                           "solve/fine_smooth", "solve/coarsest_solve"})
    EXPECT_TRUE(sections.contains(part)) << part;
  for (const char* event : {"instructions", "d1_misses", "ll_misses"}) {
    const double parts = sections["update/galerkin"][event].get<double>() +
                         sections["update/smoothers"][event].get<double>() +
                         sections["update/coarsest"][event].get<double>();
    EXPECT_GE(sections["update"][event].get<double>(), parts) << event;
  }
  // Counting marks the sections and reads nothing of the numerics: the native run's answer.
  const auto native = run_cli("run " + quoted(gate_scene()) + " --out " +
                              quoted(dir / "native.json") + " --threads 1");
  ASSERT_EQ(native.exit_code, 0) << native.err;
  const json n = json::parse(test::read_text(dir / "native.json"));
  EXPECT_EQ(a["displacement"], n["displacement"]);
  EXPECT_EQ(a["linear_iterations"], n["linear_iterations"]);
}

TEST(CliCountPhases, TheGatePassesOnItsOwnCountsAndNamesAPhaseThatGrew) {
  if (!can_count_under_valgrind()) GTEST_SKIP() << "no valgrind here, or a sanitized build";
  TempDir dir;
  std::filesystem::create_directories(dir / "suite");
  std::filesystem::copy_file(gate_scene(), dir / "suite" / "cantilever_small.json");
  const std::string gate =
      words({"python3", quoted(test::source_dir() / "ci/count-gate"), "--suite",
             quoted(dir / "suite"), "--bin", quoted(bin_dir()), "--baseline",
             quoted(dir / "baseline.json"), "--out", quoted(dir / "out")});
  const auto first = run_command(words({gate, "--update"}));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto again = run_command(gate);
  EXPECT_EQ(again.exit_code, 0) << again.err;
  // A baseline whose assembly did 2% less work: the gate fails and names the phase and scene.
  const std::filesystem::path kept = dir / "baseline.json";
  json baseline = json::parse(test::read_text(kept));
  ASSERT_EQ(baseline["records"].size(), 1u);
  json& assemble = baseline["records"][0]["phase_counts"]["sections"]["assemble"]["instructions"];
  assemble = static_cast<std::uint64_t>(assemble.get<double>() / 1.02);
  test::write_text(kept, baseline.dump());
  const auto grew = run_command(gate);
  EXPECT_EQ(grew.exit_code, 1) << grew.err;
  EXPECT_NE(grew.err.find("run cantilever_small.json: assemble instructions more by +2.0"),
            std::string::npos)
      << grew.err;
  // One that cost more: the counts fell, the baseline is stale.
  assemble = static_cast<std::uint64_t>(assemble.get<double>() * 1.02 * 1.02);
  test::write_text(kept, baseline.dump());
  const auto fell = run_command(gate);
  EXPECT_EQ(fell.exit_code, 1) << fell.err;
  EXPECT_NE(fell.err.find("the baseline is stale"), std::string::npos) << fell.err;
}

TEST(CliCountPhases, BenchGateTimesATinySuiteAndSaysWhatItCouldNotTest) {
  // ci/bench-gate with binaries built already (--base-bin, --new-bin: nothing is built): each
  // scene's runs, a record each, into OUT/base and OUT/new, then compare's verdict on them. Three
  // runs a side cannot reach compare's alpha (2 / C(6, 3) = 0.1 > 0.01), so the headline is
  // inconclusive, never "no regression".
  TempDir dir;
  std::filesystem::create_directories(dir / "suite");
  std::filesystem::copy_file(gate_scene(), dir / "suite" / "cantilever_small.json");
  const std::string gate = words({"python3", quoted(test::source_dir() / "ci/bench-gate"), "HEAD",
                                  "--suite", quoted(dir / "suite"), "--out", quoted(dir / "out"),
                                  "--runs 3 --threads 1 --no-counts"});
  const auto r =
      run_command(words({gate, "--base-bin", quoted(bin_dir()), "--new-bin", quoted(bin_dir())}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* side : {"base", "new"}) {
    int records = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir / "out" / side))
      records += entry.path().extension() == ".json";
    EXPECT_EQ(records, 3) << side;
  }
  const json verdict = json::parse(test::read_text(dir / "out" / "compare" / "compare.json"));
  EXPECT_EQ(verdict["headline"], "inconclusive") << verdict["headline"];
  EXPECT_FALSE(verdict["regression"].get<bool>());
  EXPECT_GT(verdict["untested"].get<int>(), 0);
  // One side built already and not the other: refused before anything runs.
  const auto half = run_command(words({gate, "--base-bin", quoted(bin_dir())}));
  EXPECT_EQ(half.exit_code, 2) << half.err;
  EXPECT_NE(half.err.find("--base-bin and --new-bin go together"), std::string::npos) << half.err;
}

}  // namespace
}  // namespace corofem
