// `corofem report`: every record has its schema and provenance, the oracle checks inside the table
// runs hold, REPORT.md is drawn from the JSON alone (regenerated identically, and against a golden
// file with times blanked), and a failing case is recorded instead of aborting the report.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "cholmod_oracle.hpp"
#include "core/errors.hpp"
#include "galerkin_oracle.hpp"
#include "report/case_record.hpp"
#include "report/report_config.hpp"
#include "report/report_oracles.hpp"
#include "report/scene_catalogue.hpp"
#include "report/section_progress.hpp"
#include "report/speed_accuracy.hpp"
#include "solver/petsc_solver.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using test::read_text;
using test::run_cli;
using test::TempDir;

/// What the smoke report depends on: the corofem binary and the renderer, by size and time.
std::string smoke_report_stamp() {
  std::ostringstream stamp;
  for (const fs::path& file :
       {fs::path(COROFEM_CLI), test::source_dir() / "reports" / "render_report.py"})
    stamp << file.string() << " " << fs::file_size(file) << " "
          << fs::last_write_time(file).time_since_epoch().count() << "\n";
  return stamp.str();
}

/// The smoke report, shared by the SmokeReport tests. ctest runs every test in a process of its
/// own, several at once, and under AddressSanitizer one smoke report takes five minutes: it is
/// written once per build, beside the corofem binary, under an exclusive lock, and written anew
/// when the binary or the renderer is not the one that wrote it. ctest writes it first, in
/// SmokeReportSetup (a fixture, verify/CMakeLists.txt), so that no test waits on the lock with a
/// core idle; a test binary run by hand writes it at its first use.
const fs::path& smoke_report() {
  static const fs::path out = [] {
    const fs::path root = fs::path(COROFEM_CLI).parent_path().parent_path() / "smoke-report";
    fs::create_directories(root);
    const int lock = ::open((root / "lock").c_str(), O_CREAT | O_RDWR, 0644);
    EXPECT_GE(lock, 0) << "cannot open " << root / "lock";
    if (lock >= 0) ::flock(lock, LOCK_EX);
    const std::string stamp = smoke_report_stamp();
    if (!fs::exists(root / "stamp") || read_text(root / "stamp") != stamp) {
      fs::remove_all(root / "out");
      fs::remove(root / "stamp");
      // Two threads whatever the job's count (the sanitizer job runs its gates at one): the
      // one-thread columns are then a run of their own, checked against the run to the bit.
      const auto r = run_cli("report --smoke --threads 2 --out '" + (root / "out").string() + "'");
      EXPECT_EQ(r.exit_code, 0) << r.err;
      if (r.exit_code == 0) test::write_text(root / "stamp", stamp);
    }
    if (lock >= 0) ::close(lock);  // releases the lock
    return root / "out";
  }();
  return out;
}

json load(const fs::path& file) {
  return json::parse(read_text(file));
}

bool renderer_usable() {
  return run_cli("help").exit_code == 0 &&
         std::system("python3 -c 'import sys' >/dev/null 2>&1") == 0;
}

/// The JSON records `corofem report` writes (ci/report adds mpi_scaling.json).
constexpr const char* kReportRecords[] = {"tables.json", "speed_accuracy.json", "stability.json",
                                          "stability_frames.json", "model_accuracy.json"};

void expect_keys(const json& j, std::initializer_list<const char*> keys, const std::string& where) {
  for (const char* key : keys) EXPECT_TRUE(j.contains(key)) << where << " lacks " << key;
}

void expect_context(const json& record, const std::string& file) {
  expect_keys(record, {"producer", "context", "parameters"}, file);
  expect_keys(record["context"],
              {"commit", "compiler", "flags", "cpu", "caches", "threads_used", "date"}, file);
}

TEST(SmokeReportSetup, TheCliWritesEveryRecord) {
  const fs::path& out = smoke_report();
  for (const char* file : kReportRecords) EXPECT_TRUE(fs::exists(out / file)) << out / file;
  EXPECT_TRUE(fs::exists(out / "REPORT.md")) << out / "REPORT.md";
}

TEST(SmokeReport, TablesHaveTheDocumentedSchemaAndTheOracleChecksHold) {
  const json t = load(smoke_report() / "tables.json");
  expect_context(t, "tables.json");
  ASSERT_FALSE(t["table1"].empty());
  for (const json& row : t["table1"]) {
    ASSERT_TRUE(row["completed"].get<bool>()) << row.dump();
    expect_keys(
        row,
        {"model", "tets", "vertices", "levels", "rotate_ms", "assemble_ms", "update_ms",
         "update_naive_ms", "solve_ms", "tps", "solve_accuracy", "cholmod_step_ms", "paper"},
        "table1 row");
    for (const char* key : {"rotate_ms", "assemble_ms", "update_ms", "update_naive_ms", "solve_ms",
                            "tps", "cholmod_step_ms"})
      EXPECT_GT(row[key].get<double>(), 0) << key;
    // MG-PCG stops at relative residual 1e-4; its error against CHOLMOD on the same system is at
    // most cond-bounded, and for these well-shaped meshes stays below 1e-2.
    EXPECT_LE(row["solve_accuracy"]["relative_residual_max"].get<double>(), 1e-4);
    EXPECT_LT(row["solve_accuracy"]["error_vs_cholmod_max"].get<double>(), 1e-2);
    // The roofline: every phase of the step with bytes, flops and its floor at the measured
    // STREAM bandwidth; the ratios are the record's own times over those floors.
    const json& roofline = row["roofline"];
    const double gbps = roofline["stream_triad_GBps"].get<double>();
    EXPECT_DOUBLE_EQ(gbps, t["stream_triad_GBps"].get<double>());
    EXPECT_GT(gbps, 0.1);  // any machine of this century
    double floor_sum = 0;
    for (const char* phase :
         {"checks", "rotate", "assemble", "forces", "system", "update", "solve"}) {
      SCOPED_TRACE(phase);
      const json& p = roofline["phases"][phase];
      ASSERT_TRUE(p.is_object()) << roofline.dump();
      EXPECT_GT(p["bytes"].get<double>(), 0);
      EXPECT_GT(p["flops"].get<double>(), 0);
      const double floor_ms =
          std::max(p["bytes"].get<double>() / (gbps * 1e6),
                   p["flops"].get<double>() / (roofline["dense_gflops"].get<double>() * 1e6));
      EXPECT_NEAR(p["floor_ms"].get<double>(), floor_ms, 1e-12 * floor_ms);
      EXPECT_NEAR(p["over_floor"].get<double>(),
                  p["measured_ms"].get<double>() / p["floor_ms"].get<double>(),
                  1e-9 * p["over_floor"].get<double>());
      floor_sum += p["floor_ms"].get<double>();
    }
    EXPECT_NEAR(roofline["floor_ms"].get<double>(), floor_sum, 1e-12 * floor_sum);
    // The update's parts add up to the update's traffic, except the two the solver defers to its
    // solves at two or more threads and three or more levels (the coarsest factorization and the
    // smoothers' set-up run beside the next solve's first descent): those count in the solve's
    // traffic (StepRoofline's gates check that move where the smoke scene does not defer).
    const bool deferred = row["coarsest_factorization_in"] == "solve";
    EXPECT_EQ(deferred, t["threads"].get<int>() > 1 && row["levels"].get<int>() >= 3)
        << "MultigridSolver::defers_update";
    double update_bytes = 0, deferred_bytes = 0;
    for (const char* part : {"galerkin", "smoothers", "coarsest"}) {
      ASSERT_TRUE(roofline["update_parts"][part].is_object()) << part;
      EXPECT_GT(roofline["update_parts"][part]["measured_ms"].get<double>(), 0) << part;
      const double bytes = roofline["update_parts"][part]["bytes"].get<double>();
      (deferred && std::string(part) != "galerkin" ? deferred_bytes : update_bytes) += bytes;
    }
    EXPECT_NEAR(update_bytes, roofline["phases"]["update"]["bytes"].get<double>(),
                1e-12 * update_bytes);
    if (deferred) {
      EXPECT_GT(roofline["phases"]["solve"]["bytes"].get<double>(), deferred_bytes);
    }
    EXPECT_DOUBLE_EQ(roofline["step_ms"].get<double>(), row["step_ms"].get<double>());
    // Every phase runs inside the step's clock: each step's remainder, and so their median, is >=
    // 0.
    EXPECT_GE(roofline["untimed_ms"].get<double>(), 0.0);
    // Table 1 at one thread and at the run's count: the same phases, each with its roofline; at
    // one thread the record's own columns are the one-thread ones.
    EXPECT_EQ(row["threads"], t["threads"]);
    EXPECT_EQ(t["threads"].get<int>(), t["context"]["threads_used"].get<int>());
    for (const char* set : {"phases_ms", "one_thread"})
      for (const char* phase :
           {"checks", "rotate", "assemble", "forces", "system", "update", "solve", "step", "tps"})
        EXPECT_GT(row[set][phase].get<double>(), 0) << set << " " << phase;
    EXPECT_DOUBLE_EQ(row["phases_ms"]["step"].get<double>(), row["step_ms"].get<double>());
    EXPECT_TRUE(row["one_thread"]["roofline"]["phases"].is_object());
    EXPECT_DOUBLE_EQ(row["one_thread"]["roofline"]["stream_triad_GBps"].get<double>(),
                     t["one_thread_roofs"]["stream_triad_GBps"].get<double>());
    // At two threads (the smoke report's, in every job) the one-thread columns come from a run
    // of their own, which must do the same work to the bit: same solver iterations, same
    // displacements.
    const json& one = row["one_thread"];
    EXPECT_EQ(t["threads"].get<int>(), 2);
    EXPECT_TRUE(one["separate_run"].get<bool>());
    EXPECT_EQ(one["linear_iterations"], row["linear_iterations"]);
    EXPECT_GT(row["linear_iterations"].get<int>(), 0);
    EXPECT_TRUE(one["same_displacement_bits"].get<bool>());
    // Our stream against PETSc's MatPtAP on the same matrices, where PETSc is built.
    if (have_petsc()) {
      const json& g = row["galerkin_vs_matptap"];
      ASSERT_TRUE(g.is_object()) << row.dump();
      EXPECT_GT(g["matptap_ms"].get<double>(), 0);
      EXPECT_GT(g["galerkin_one_thread_ms"].get<double>(), 0);
      EXPECT_EQ(g["galerkin"], "gather");
      EXPECT_NEAR(g["matptap_over_galerkin_one_thread"].get<double>(),
                  g["matptap_ms"].get<double>() / g["galerkin_one_thread_ms"].get<double>(),
                  1e-9 * g["matptap_over_galerkin_one_thread"].get<double>());
    } else {
      EXPECT_TRUE(row["galerkin_vs_matptap"].is_null());
    }
  }
  // The solvers users would pick instead: all three for every table row, and the two AMGs again
  // with their setup reused; run where PETSc is built, a recorded failure naming the library
  // where it is not.
  ASSERT_EQ(t["rival_solvers"].size(), 5 * t["table1"].size());
  int reused = 0;
  for (const json& row : t["rival_solvers"]) {
    if (row["setup_reuse"].get<bool>()) {
      ++reused;
      EXPECT_NE(row["solver"], "petsc-mg");
    }
    if (have_petsc()) {
      ASSERT_TRUE(row["completed"].get<bool>()) << row.dump();
      EXPECT_GE(row["iterations"].get<double>(), 1.0);
      EXPECT_GT(row["update_ms"].get<double>(), 0);
      EXPECT_NEAR(row["step_over_mgpcg"].get<double>(),
                  row["step_ms"].get<double>() / row["mgpcg_step_ms"].get<double>(),
                  1e-9 * row["step_over_mgpcg"].get<double>());
    } else {
      EXPECT_FALSE(row["completed"].get<bool>());
      EXPECT_NE(row["error"]["message"].get<std::string>().find("needs PETSc"), std::string::npos)
          << row.dump();
    }
  }
  EXPECT_EQ(reused, 2 * static_cast<int>(t["table1"].size()));
  for (const char* section : {"table2", "small_strain", "jacobi_pcg"}) {
    ASSERT_FALSE(t[section].empty()) << section;
    for (const json& row : t[section])
      EXPECT_TRUE(row["completed"].get<bool>()) << section << row.dump();
  }
  // Jacobi-PCG on each scene and 100x stiffer: its CG iterations grow as the condition number's
  // square root (10x in theory for 100x E, once K dominates M / dt^2), MG-PCG's far less.
  ASSERT_EQ(t["jacobi_pcg"].size(), 2 * t["table1"].size());
  for (std::size_t k = 0; k + 1 < t["jacobi_pcg"].size(); k += 2) {
    const json& soft = t["jacobi_pcg"][k];
    const json& stiff = t["jacobi_pcg"][k + 1];
    ASSERT_EQ(soft["young_scale"].get<double>(), 1.0);
    ASSERT_EQ(stiff["young_scale"].get<double>(), 100.0);
    const double jacobi_growth =
        stiff["iterations"].get<double>() / soft["iterations"].get<double>();
    const double mgpcg_growth =
        stiff["mgpcg_iterations"].get<double>() / soft["mgpcg_iterations"].get<double>();
    EXPECT_GT(jacobi_growth, 2.0) << stiff.dump();
    EXPECT_GT(jacobi_growth, 1.5 * mgpcg_growth) << stiff.dump();
  }
  expect_keys(t["table2"][0], {"model", "tps", "paper_tps"}, "table2 row");
  // Multigrid quality: both hierarchies for every table row, each coarsening the fine mesh of
  // that row, with a contracting V-cycle.
  ASSERT_EQ(t["multigrid"].size(), 2 * t["table1"].size());
  std::set<std::string> hierarchies;
  for (const json& row : t["multigrid"]) {
    ASSERT_TRUE(row["completed"].get<bool>()) << row.dump();
    expect_keys(row,
                {"hierarchy", "levels", "level_vertices", "operator_complexity", "rho", "vcycles",
                 "mgpcg_iterations", "setup_ms", "update_ms", "solve_ms", "step_ms"},
                "multigrid row");
    hierarchies.insert(row["hierarchy"].get<std::string>());
    const json& sizes = row["level_vertices"];
    ASSERT_EQ(sizes.size(), row["levels"].get<std::size_t>());
    EXPECT_EQ(sizes[0], t["table1"][0]["vertices"]);
    for (std::size_t h = 1; h < sizes.size(); ++h) EXPECT_LT(sizes[h], sizes[h - 1]) << row.dump();
    EXPECT_GT(row["operator_complexity"].get<double>(), 1.0);
    EXPECT_GT(row["rho"].get<double>(), 0.0);
    EXPECT_LT(row["rho"].get<double>(), 1.0);
    EXPECT_GE(row["mgpcg_iterations"].get<double>(), 1.0);
  }
  EXPECT_EQ(hierarchies, (std::set<std::string>{"meshes", "lattice"}));
  expect_keys(t["small_strain"][0], {"tps", "volume_change", "corotated_volume_change"},
              "small_strain row");
  // The verification summary: the same oracles as the gates, on the report's own states.
  ASSERT_FALSE(t["verification"].empty());
  for (const json& check : t["verification"][0]["checks"]) {
    const std::string oracle = check["oracle"];
    const double largest = check["largest"];
    ASSERT_GE(largest, 0) << oracle;  // negative would mean "not run"
    if (oracle.find("R A R^T") != std::string::npos) {
      EXPECT_LT(largest, 1e-12);
    }
    if (oracle.find("energy-exact") != std::string::npos) {
      EXPECT_LT(largest, 1e-8);
    }
  }
}

TEST(SmokeReport, SpeedAccuracyPointsAndParetoFront) {
  const json s = load(smoke_report() / "speed_accuracy.json");
  expect_context(s, "speed_accuracy.json");
  ASSERT_FALSE(s["scenes"].empty());
  for (const json& scene : s["scenes"]) {
    ASSERT_TRUE(scene["completed"].get<bool>()) << scene.dump();
    std::set<std::string> sweeps;
    for (const json& p : scene["points"]) {
      expect_keys(p, {"sweep", "setting", "label", "completed"}, "point");
      ASSERT_TRUE(p["completed"].get<bool>()) << p.dump();
      expect_keys(p, {"time_per_step_ms", "rel_error", "pareto"}, "point");
      sweeps.insert(p["sweep"]);
    }
    EXPECT_EQ(sweeps, (std::set<std::string>{"solver", "rotation", "resolution"}));
    expect_keys(scene["cheapest_meeting_target"], {"solver", "rotation", "resolution"}, "scene");
  }
}

TEST(Report, ParetoFrontIsTheSetOfUndominatedPoints) {
  json points = json::array();
  auto add = [&](double time, double error) {
    points.push_back({{"completed", true}, {"time_per_step_ms", time}, {"rel_error", error}});
  };
  add(1, 1e-2);  // front
  add(2, 1e-3);  // front
  add(3, 1e-2);  // dominated by (1, 1e-2) and (2, 1e-3)
  add(4, 1e-6);  // front
  add(5, 1e-6);  // dominated by (4, 1e-6)
  points.push_back({{"completed", false}, {"error", {{"message", "failed"}}}});
  mark_pareto_front(points);
  const bool expected[] = {true, true, false, true, false};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(points[i]["pareto"].get<bool>(), expected[i]) << i;
  EXPECT_FALSE(points[5].contains("pareto"));
}

TEST(SmokeReport, StabilityRunsHaveTheDocumentedSchema) {
  const json st = load(smoke_report() / "stability.json");
  expect_context(st, "stability.json");
  expect_keys(st, {"thresholds", "runs", "scenes", "verdicts"}, "stability.json");
  ASSERT_FALSE(st["runs"].empty());
  std::set<std::string> methods, integrators;
  for (const json& run : st["runs"]) {
    expect_keys(
        run,
        {"scene", "method", "integrator", "dt", "status", "flutter_rms_rad", "flutter_max_rad",
         "inverted_max", "diverged_step", "asymmetry", "energy_error", "cause"},
        "run");
    EXPECT_FALSE(run.contains("series")) << "the per-step series belong in stability_frames.json";
    const std::string status = run["status"];
    EXPECT_TRUE(status == "stable" || status == "flutter" || status == "diverged") << status;
    EXPECT_EQ(run["diverged_step"].is_null(), status != "diverged");
    if (status == "stable") {
      EXPECT_TRUE(run["cause"].is_null());
    }
    methods.insert(run["method"]);
    integrators.insert(run["integrator"]);
  }
  EXPECT_EQ(methods.size(), 7u);  // every extractor
  EXPECT_EQ(integrators, (std::set<std::string>{"linear-implicit", "newton"}));
  for (const std::string& method : methods) EXPECT_TRUE(st["verdicts"].contains(method)) << method;
  // The charts' frames beside it: one series per run, in the runs' order, as long as the run.
  const json frames = load(smoke_report() / "stability_frames.json");
  expect_context(frames, "stability_frames.json");
  expect_keys(frames, {"series", "poses", "surfaces"}, "stability_frames.json");
  ASSERT_EQ(frames["series"].size(), st["runs"].size());
  for (std::size_t i = 0; i < st["runs"].size(); ++i) {
    const json& series = frames["series"][i];
    ASSERT_TRUE(series.contains("rotation_change_max_rad")) << i;
    EXPECT_EQ(series["rotation_change_max_rad"].size(), st["runs"][i]["steps_run"].get<size_t>())
        << i;
  }
  EXPECT_FALSE(frames["poses"].empty());
}

TEST(SmokeReport, ModelAccuracyHasTheDocumentedSchema) {
  const json ma = load(smoke_report() / "model_accuracy.json");
  expect_context(ma, "model_accuracy.json");
  if (ma.contains("skipped")) GTEST_SKIP() << ma["skipped"];
  ASSERT_EQ(ma["cases"].size(), 1u);  // smoke: the small cantilever
  const json& c = ma["cases"][0];
  ASSERT_TRUE(c["completed"].get<bool>()) << c.dump();
  // The linear solves agree to CalculiX's printed digits; every method ran against NLGEOM.
  EXPECT_LT(c["linear"]["against_calculix_linear"]["max"].get<double>(), 1e-6);
  EXPECT_EQ(c["methods"].size(), 7u);
  for (const json& m : c["methods"]) {
    ASSERT_TRUE(m["completed"].get<bool>()) << m.dump();
    EXPECT_TRUE(m["converged"].get<bool>()) << m["method"];
    // Same mesh and loads: corotated against St. Venant-Kirchhoff at strains of about 1%.
    EXPECT_LT(m["against_calculix_nlgeom"]["l2"].get<double>(), 0.05) << m["method"];
  }
}

TEST(SmokeReport, MarkdownIsRedrawnFromTheJsonAlone) {
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  const fs::path& out = smoke_report();
  ASSERT_TRUE(fs::exists(out / "REPORT.md"));
  TempDir copy;
  for (const char* file : kReportRecords) fs::copy_file(out / file, copy / file);
  const std::string script = (test::source_dir() / "reports" / "render").string();
  ASSERT_EQ(std::system(("'" + script + "' '" + copy.path().string() + "' 2>/dev/null").c_str()),
            0);
  EXPECT_EQ(read_text(copy / "REPORT.md"), read_text(out / "REPORT.md"));
  // The same charts, drawn from the copy.
  std::set<std::string> original, redrawn;
  if (fs::exists(out / "charts"))
    for (const auto& e : fs::directory_iterator(out / "charts"))
      original.insert(e.path().filename());
  if (fs::exists(copy / "charts"))
    for (const auto& e : fs::directory_iterator(copy / "charts"))
      redrawn.insert(e.path().filename());
  EXPECT_EQ(original, redrawn);
}

fs::path golden_dir() {
  return test::source_dir() / "verify" / "golden" / "report";
}

/// Copies the golden JSON records into `dir` (`edit_tables` may change tables.json first) and
/// runs the renderer on them with `options`, its stderr to `stderr_file`; returns its exit status.
int render_golden_fixture(const TempDir& dir, const std::string& options,
                          const std::string& stderr_file,
                          const std::function<void(json&)>& edit_tables = {}) {
  for (const char* file : kReportRecords) fs::copy_file(golden_dir() / file, dir / file);
  fs::copy_file(golden_dir() / "mpi_scaling.json", dir / "mpi_scaling.json");
  if (edit_tables) {
    json tables = json::parse(read_text(dir / "tables.json"));
    edit_tables(tables);
    test::write_text(dir / "tables.json", tables.dump());
  }
  const std::string script = (test::source_dir() / "reports" / "render").string();
  return std::system(("'" + script + "' '" + dir.path().string() + "' " + options + " 2>'" +
                      stderr_file + "' >/dev/null")
                         .c_str());
}

TEST(Report, SinceTheSnapshotShowsWhatMovedWithItsInterval) {
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir dir;
  // A verdict as corofem compare writes it: one phase slower, one counter up, the rest the same.
  const json verdict = {
      {"producer", "corofem compare"},
      {"base_context", {{"commit", "824896a52a2001bbccd"}, {"date", "2026-12-05"}}},
      {"options", {{"alpha", 0.01}, {"threshold", 0.05}}},
      {"regression", true},
      {"verdicts", {{"slower", 1}, {"increased", 1}, {"same", 1}}},
      {"warnings",
       {"cpu differs: BASE AMD EPYC, NEW Intel Xeon (timings compare the machines "
        "as much as the code)"}},
      {"rows",
       {{{"case", "table1 bunny-11k"},
         {"threads", 2},
         {"quantity", "solve"},
         {"kind", "timed"},
         {"verdict", "slower"},
         {"base", 2.5},
         {"new", 2.8},
         {"test", {{"ratio", 1.12}, {"interval", {1.08, 1.16}}}}},
        {{"case", "table1 bunny-11k"},
         {"threads", 2},
         {"quantity", "linear_iterations"},
         {"kind", "counter"},
         {"verdict", "increased"},
         {"base", 138},
         {"new", 140}},
        {{"case", "table1 bunny-11k"},
         {"threads", 2},
         {"quantity", "step"},
         {"kind", "timed"},
         {"verdict", "same"},
         {"base", 4.9},
         {"new", 4.95},
         {"test", {{"ratio", 1.01}, {"interval", {0.98, 1.04}}}}}}}};
  ASSERT_EQ(render_golden_fixture(
                dir, "", "/dev/null",
                [&](json&) { test::write_text(dir / "since_snapshot.json", verdict.dump()); }),
            0);
  const std::string md = read_text(dir / "REPORT.md");
  // Hand-written expectations, not the renderer's own output captured once.
  EXPECT_NE(md.find("## Since the last published snapshot"), std::string::npos);
  EXPECT_NE(md.find("snapshot of commit `824896a52` (2026-12-05): **a regression**"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- warning: cpu differs: BASE AMD EPYC, NEW Intel Xeon"), std::string::npos);
  EXPECT_NE(md.find("| table1 bunny-11k | 2 | solve | timed | 2.5 | 2.8 | 1.12 | 1.08-1.16 | "
                    "slower |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| linear_iterations | counter | 138 | 140 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| step | timed"), std::string::npos) << "a row that did not move is listed";
}

/// printf's rendering of `value` in `format`: the expectation's own arithmetic and format.
std::string printed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

TEST(Report, TableOneShowsItsRecordsNumbers) {
  // Hand-written expectations: Table 1's row drawn from the golden tables.json carries that
  // record's numbers, each worked out here from the record (ms to 3 significant digits, steps per
  // second 1000 / step ms to the unit, errors and ratios to 2), not the renderer's output captured.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir dir;
  ASSERT_EQ(render_golden_fixture(dir, "", "/dev/null"), 0);
  const json row = json::parse(read_text(golden_dir() / "tables.json"))["table1"][0];
  const json& accuracy = row["solve_accuracy"];
  const std::string expected =
      "| " + row["model"].get<std::string>() + " | " + std::to_string(row["tets"].get<int>()) +
      " | " + std::to_string(row["vertices"].get<int>()) + " | " +
      std::to_string(row["levels"].get<int>()) + " | " + printed("%.3g", row["rotate_ms"]) + " | " +
      printed("%.3g", row["assemble_ms"]) + " | " + printed("%.3g", row["update_ms"]) + " | " +
      printed("%.3g", row["update_naive_ms"]) + " | " + printed("%.3g", row["solve_ms"]) + " | " +
      printed("%.0f", 1000 / row["step_ms"].get<double>()) + " | " +
      printed("%.1e", accuracy["relative_residual_max"]) + " / " +
      printed("%.1e", accuracy["error_vs_cholmod_max"]) + " | " +
      printed("%.3g", row["cholmod_step_ms"]) + " | " +
      printed("%.2g", row["cholmod_step_ms"].get<double>() / row["step_ms"].get<double>()) + " |";
  const std::string md = read_text(dir / "REPORT.md");
  EXPECT_NE(md.find(expected), std::string::npos) << "expected\n"
                                                  << expected << "\nin\n"
                                                  << md.substr(0, 1500);
  // The targets: the step over its roofline floor, at one thread against 1.5x (judged), at two
  // judged only where the record's handoff says the cores were close (under 100 ns).
  const double one = row["one_thread"]["roofline"]["over_floor"];
  const std::string target_one = "| " + row["model"].get<std::string>() + " | 1 | " +
                                 printed("%.2g", one) + " | " + (one <= 1.5 ? "met" : "not met");
  EXPECT_NE(md.find(target_one), std::string::npos) << target_one;
  const json handoff = json::parse(read_text(golden_dir() / "tables.json"))["context"].value(
      "core_to_core_ns", json(nullptr));
  const double two = row["roofline"]["over_floor"];
  const std::string judged = !handoff.is_number()           ? "not judged"
                             : handoff.get<double>() >= 100 ? "not judged"
                             : two <= 1.5                   ? "met"
                                                            : "not met";
  const std::string target_two =
      "| " + row["model"].get<std::string>() + " | 2 | " + printed("%.2g", two) + " | " + judged;
  EXPECT_NE(md.find(target_two), std::string::npos) << target_two;
}

TEST(Report, SinceTheSnapshotDrawsARealComparison) {
  // A compare.json as corofem compare writes it, from two folders of Table 1 records: 8 runs a
  // side, NEW's solve 30% slower. The section shows that row with compare's own ratio.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir dir;
  const json tables = json::parse(read_text(golden_dir() / "tables.json"));
  for (const char* side : {"base", "new"}) fs::create_directories(dir / side);
  for (int run = 0; run < 8; ++run) {
    json base = tables, slow = tables;
    for (json* t : {&base, &slow}) {
      json& samples = (*t)["table1"][0]["samples_ms"];
      for (auto& [phase, values] : samples.items())
        for (json& v : values) v = v.get<double>() * (1 + 0.001 * run);  // distinct runs
    }
    for (json& v : slow["table1"][0]["samples_ms"]["solve"]) v = v.get<double>() * 1.3;
    test::write_text(dir / "base" / ("r" + std::to_string(run) + ".json"), base.dump());
    test::write_text(dir / "new" / ("r" + std::to_string(run) + ".json"), slow.dump());
  }
  const test::CliResult compared =
      test::run_cli("compare '" + (dir / "base").string() + "' '" + (dir / "new").string() +
                    "' --out '" + (dir / "compare").string() + "'");
  ASSERT_EQ(compared.exit_code, 1) << compared.err;  // a regression
  const json verdict = json::parse(read_text(dir / "compare" / "compare.json"));
  json solve;
  for (const json& r : verdict["rows"])
    if (r["quantity"] == "solve" && r["case"] != "all cases" &&
        r["threads"] == tables["context"]["threads_used"])  // the slowed runs, not one_thread's
      solve = r;
  ASSERT_FALSE(solve.is_null());
  EXPECT_EQ(solve["verdict"], "slower");
  EXPECT_NEAR(solve["test"]["ratio"].get<double>(), 1.3, 0.01);
  TempDir render;
  ASSERT_EQ(render_golden_fixture(
                render, "", "/dev/null",
                [&](json&) { test::write_text(render / "since_snapshot.json", verdict.dump()); }),
            0);
  const std::string md = read_text(render / "REPORT.md");
  const std::string expected = "| " + solve["case"].get<std::string>() + " | " +
                               std::to_string(solve["threads"].get<int>()) + " | solve | timed | " +
                               printed("%.3g", solve["base"]) + " | " +
                               printed("%.3g", solve["new"]) + " | " +
                               printed("%.3g", solve["test"]["ratio"]) + " | ";
  EXPECT_NE(md.find(expected), std::string::npos) << expected << "\n" << md;
  EXPECT_NE(md.find("**a regression**"), std::string::npos);
}

TEST(Report, SinceTheSnapshotStaysAGlance) {
  // A comparison with 100 rows that moved and cases it left out: the section keeps its headline,
  // the lines of what it could not pair, and the 20 largest moves, under 40 lines.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  json rows = json::array();
  for (int k = 0; k < 100; ++k)
    rows.push_back({{"case", "table1 quadruped-" + std::to_string(k)},
                    {"threads", 2},
                    {"quantity", "solve"},
                    {"kind", "timed"},
                    {"verdict", "slower"},
                    {"base", 1.0},
                    {"new", 1.1 + 0.01 * k},
                    {"test", {{"ratio", 1.1 + 0.01 * k}, {"interval", {1.05, 1.2 + 0.01 * k}}}}});
  const json verdict = {{"producer", "corofem compare"},
                        {"base_context", {{"commit", "abc"}, {"date", "d"}}},
                        {"options", {{"alpha", 0.01}, {"threshold", 0.05}}},
                        {"regression", true},
                        {"verdicts", {{"slower", 100}}},
                        {"unpaired", {"3 cases only BASE ran: table1 bunny-11k, ..."}},
                        {"rows", rows}};
  TempDir dir;
  ASSERT_EQ(render_golden_fixture(
                dir, "", "/dev/null",
                [&](json&) { test::write_text(dir / "since_snapshot.json", verdict.dump()); }),
            0);
  const std::string md = read_text(dir / "REPORT.md");
  const std::size_t start = md.find("## Since the last published snapshot");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = md.find("\n## ", start + 1);
  const std::string section = md.substr(start, end - start);
  EXPECT_LT(std::count(section.begin(), section.end(), '\n'), 40) << section;
  EXPECT_NE(section.find("- not compared: 3 cases only BASE ran"), std::string::npos) << section;
  EXPECT_NE(section.find("table1 quadruped-99"), std::string::npos);   // the largest move is shown
  EXPECT_EQ(section.find("table1 quadruped-0 |"), std::string::npos);  // the smallest is not
  EXPECT_NE(section.find("80 more in since_snapshot/compare.md"), std::string::npos) << section;
}

TEST(Report, TablesAsLaTeXCarryTheMarkdownsNumbersAndCompile) {
  // Every Markdown table of REPORT.md is also tables/NN-slug.tex (booktabs), and tables/all.tex
  // inputs them all: its cells, with LaTeX's escapes undone, are the Markdown's; pdflatex compiles
  // the document (ci/setup installs it).
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir dir;
  ASSERT_EQ(render_golden_fixture(dir, "", "/dev/null"), 0);
  const std::string md = read_text(dir / "REPORT.md");
  std::vector<std::string> markdown_rows;  // every table row, cells joined by " | "
  std::istringstream lines(md);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("| ", 0) == 0) markdown_rows.push_back(line.substr(2, line.size() - 4));
  std::vector<fs::path> tex;
  for (const auto& e : fs::directory_iterator(dir / "tables"))
    if (e.path().extension() == ".tex" && e.path().filename() != "all.tex") tex.push_back(e.path());
  EXPECT_GE(tex.size(), 8u);
  std::size_t tex_rows = 0;
  for (const fs::path& file : tex) {
    std::istringstream rows(read_text(file));
    for (std::string line; std::getline(rows, line);) {
      if (line.size() < 3 || line.substr(line.size() - 3) != " \\\\") continue;
      std::string plain = line.substr(0, line.size() - 3);
      plain = std::regex_replace(plain, std::regex(R"(\\textbf\{([^}]*)\})"), "**$1**");
      plain = std::regex_replace(plain, std::regex(R"(\\texttt\{([^}]*)\})"), "`$1`");
      plain = std::regex_replace(plain, std::regex(" & "), " | ");
      plain = std::regex_replace(plain, std::regex(R"(\\([_%&#$]))"), "$1");
      ++tex_rows;
      if (plain.find('\\') != std::string::npos) continue;  // other escapes: not undone here
      EXPECT_NE(std::find(markdown_rows.begin(), markdown_rows.end(), plain), markdown_rows.end())
          << file.filename() << ": " << plain;
    }
  }
  EXPECT_EQ(tex_rows, markdown_rows.size());  // every row, headers included, once
  if (std::system("pdflatex --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no pdflatex here (ci/setup installs texlive-latex-recommended)";
  const std::string compile = "cd '" + (dir / "tables").string() +
                              "' && pdflatex -interaction=nonstopmode -halt-on-error all.tex > "
                              "latex.log 2>&1";
  EXPECT_EQ(std::system(compile.c_str()), 0) << read_text(dir / "tables" / "latex.log");
  EXPECT_TRUE(fs::exists(dir / "tables" / "all.pdf"));
}

TEST(Report, MarkdownMatchesTheGoldenFileWithTimesBlanked) {
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  // verify/golden/report: JSON records of a smoke run and the REPORT.md drawn from them with
  // --blank-times. A change of the report's format shows here; regenerate with
  // reports/render verify/golden/report --blank-times and review the diff.
  TempDir copy;
  ASSERT_EQ(render_golden_fixture(copy, "--blank-times", "/dev/null"), 0);
  std::string expected = read_text(golden_dir() / "REPORT.md"), got = read_text(copy / "REPORT.md");
  if (got.find("matplotlib was not available") != std::string::npos)
    GTEST_SKIP() << "no matplotlib: the golden file has the charts' links";
  EXPECT_EQ(got, expected);
}

TEST(SmokeReport, GoldenFixturesHaveTheSchemaTheCodeWrites) {
  // Every field the renderer reads is in the golden records exactly where it is in the records
  // the current code writes (the smoke report), so the golden REPORT.md tests the report as it is
  // drawn today. On a failure: reports/regenerate_golden (from a clean commit), review the diff.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  if (!have_petsc())
    GTEST_SKIP()
        << "the golden records come from a build with PETSc (its rival solvers and MatPtAP "
           "fields); this build has none, so its records differ there by design";
  const fs::path& out = smoke_report();
  TempDir dir;
  const std::string command =
      "python3 '" + (test::source_dir() / "reports" / "schema_check.py").string() + "' '" +
      golden_dir().string() + "' '" + out.string() + "' > '" + (dir / "drift").string() + "' 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << read_text(dir / "drift");
  // tables, speed-accuracy, stability and its frames, model accuracy (the smoke run has no MPI).
  EXPECT_NE(read_text(dir / "drift").find("5 record file(s) compared"), std::string::npos)
      << read_text(dir / "drift");
}

TEST(SmokeReport, PublishedSnapshotHasTheSchemaTheCodeWrites) {
  // reports/ (the published snapshot, drawn from the models) holds every field the renderer reads
  // in the records the current code writes, so a change to the records comes with a fresh
  // snapshot (reports/publish, from a clean commit). The snapshot may hold more: the models' rows.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  if (!have_petsc())
    GTEST_SKIP() << "the snapshot comes from a build with PETSc (its rival solvers' fields)";
  const fs::path& out = smoke_report();
  TempDir dir;
  const std::string command =
      "python3 '" + (test::source_dir() / "reports" / "schema_check.py").string() +
      "' --snapshot '" + out.string() + "' '" + (test::source_dir() / "reports").string() +
      "' > '" + (dir / "drift").string() + "' 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << read_text(dir / "drift");
  EXPECT_EQ(read_text(dir / "drift").find(" 0 record file(s) compared"), std::string::npos)
      << read_text(dir / "drift");
}

TEST(Report, ReadmeHeadlineIsThePublishedSnapshots) {
  // The front page's Table 1 (README.md, between its headline markers) is drawn from the
  // published snapshot's tables.json, so its numbers, commit and machine are the snapshot's.
  // On a failure: reports/readme_headline.py README.md reports (reports/publish runs it).
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the script cannot run";
  TempDir dir;
  // readme_headline.py --check on a README against reports/; its messages in dir/drift
  const auto check = [&](const fs::path& readme) {
    const std::string command =
        "python3 '" + (test::source_dir() / "reports" / "readme_headline.py").string() +
        "' --check '" + readme.string() + "' '" + (test::source_dir() / "reports").string() +
        "' > '" + (dir / "drift").string() + "' 2>&1";
    return std::system(command.c_str());
  };
  EXPECT_EQ(check(test::source_dir() / "README.md"), 0) << read_text(dir / "drift");
  // and the check fails on a headline that is not the snapshot's
  std::string stale = read_text(test::source_dir() / "README.md");
  const std::size_t row = stale.find("| dragon | ");
  ASSERT_NE(row, std::string::npos);
  stale.insert(row + 2, "old ");
  { std::ofstream(dir / "README.md") << stale; }
  EXPECT_NE(check(dir / "README.md"), 0);
}

TEST(Report, SaysWhenTheSolveCarriedTheCoarsestFactorization) {
  // At two or more threads MG-PCG runs the coarsest factorization in the solve phase: the
  // thread table says so when a row's record does, and only then.
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  const std::string note = "`MultigridSolver::defers_update`";
  const auto factorized_in = [](const char* phase) {
    return [phase](json& tables) {
      for (const char* table : {"table1", "multigrid"})
        for (json& row : tables[table]) row["coarsest_factorization_in"] = phase;
    };
  };
  TempDir plain, deferred;
  ASSERT_EQ(render_golden_fixture(plain, "--blank-times", "/dev/null", factorized_in("update")), 0);
  ASSERT_EQ(render_golden_fixture(deferred, "--blank-times", "/dev/null", factorized_in("solve")),
            0);
  EXPECT_EQ(read_text(plain / "REPORT.md").find(note), std::string::npos);
  EXPECT_NE(read_text(deferred / "REPORT.md").find(note), std::string::npos);
}

TEST(Report, BareSurfaceRowsAreNamedSoInBothMultigridTables) {
  // A row whose coarse levels came from the bare surface is labelled so in the quality table and
  // in the table of where its time goes (the second once printed only "meshes", making a bare row
  // indistinguishable from the models' own levels).
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir copy;
  ASSERT_EQ(render_golden_fixture(copy, "--blank-times", "/dev/null",
                                  [](json& tables) {
                                    for (json& row : tables["multigrid"])
                                      if (row["hierarchy"] == "meshes")
                                        row["coarse_meshes"] = "derived from the bare surface";
                                  }),
            0);
  const std::string report = read_text(copy / "REPORT.md");
  std::size_t labelled = 0;
  for (std::size_t at = 0; (at = report.find("| meshes, bare surface |", at)) != std::string::npos;
       ++at)
    ++labelled;
  EXPECT_EQ(labelled, 2u) << report;  // the fixture's one meshes row, once in each table
}

TEST(Report, RendererDrawsEveryChartOfTheFixtureWithoutWarnings) {
  if (!renderer_usable()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir copy;
  const fs::path err = copy / "stderr.txt";
  ASSERT_EQ(render_golden_fixture(copy, "", err.string()), 0);
  const std::string messages = read_text(err);
  const std::string report = read_text(copy / "REPORT.md");
  if (report.find("matplotlib was not available") != std::string::npos)
    GTEST_SKIP() << "no matplotlib";
  EXPECT_EQ(messages.find("Warning"), std::string::npos) << messages;
  // Every chart REPORT.md links to exists.
  std::size_t at = 0, links = 0;
  while ((at = report.find("](charts/", at)) != std::string::npos) {
    const std::size_t end = report.find(')', at);
    const std::string name = report.substr(at + 2, end - at - 2);
    EXPECT_TRUE(fs::exists(copy / name)) << name;
    ++links;
    at = end;
  }
  EXPECT_GE(links, 4u);  // phases, speed-accuracy, two flutter charts
}

TEST(Report, FailingCasesAreRecordedAndTheReportGoesOn) {
  // A models folder whose surfaces are not STL: every table, sweep and model case fails with an
  // input error naming the file; the report still writes all its records and exits 0.
  TempDir models, out;
  for (const char* m : {"bunny", "horse", "dragon"})
    for (const char* level : {"_L0.stl", "_L1.stl"})
      test::write_text(models / (std::string(m) + level), "solid broken\nthis is not an stl\n");
  const auto r = run_cli("report --smoke --no-render --tables-only --models '" +
                         models.path().string() + "' --out '" + out.path().string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json t = load(out / "tables.json");
  ASSERT_EQ(t["table1"].size(), 3u);
  for (const json& row : t["table1"]) {
    EXPECT_FALSE(row["completed"].get<bool>());
    EXPECT_EQ(row["error"]["kind"], "input");
    EXPECT_NE(row["error"]["message"].get<std::string>().find("_L1.stl"), std::string::npos)
        << row.dump();
  }
}

TEST(Report, VtuFramesOnRequest) {
  TempDir out;
  const auto r =
      run_cli("report --smoke --stability-only --only bar-twist --vtu --no-render --out '" +
              out.path().string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Every 10th step of every extractor's run (smoke: 12 steps, so frame 10), as VTK XML.
  for (const char* method : {"energy-newton", "energy-exact", "polar", "polar-fixed",
                             "polar-smoothed", "qr", "mueller2016"}) {
    const fs::path frame =
        out / "vtu" / "bar-twist" / (std::string(method) + "-linear-implicit") / "frame_00010.vtu";
    ASSERT_TRUE(fs::exists(frame)) << frame;
    EXPECT_NE(read_text(frame).find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos)
        << frame;
  }
}

TEST(Report, RecordCaseKeepsTheErrorKind) {
  const json ok = record_case({{"id", 1}}, [] { return json{{"value", 2}}; });
  EXPECT_TRUE(ok["completed"].get<bool>());
  EXPECT_EQ(ok["value"], 2);
  const json bad =
      record_case({{"id", 1}}, []() -> json { throw NumericalFault("NaN at step 3"); });
  EXPECT_FALSE(bad["completed"].get<bool>());
  EXPECT_EQ(bad["error"]["kind"], "numerical");
  EXPECT_EQ(bad["id"], 1);
}

/// The main job's default (issue 38): Table 1 at the paper's three sizes, the comparison tables
/// where they cost seconds (the Jacobi-PCG table on every model file); --full at every size.
TEST(Report, StandardModeRunsTableOneAtThePapersThreeSizes) {
  ReportConfig standard;
  ASSERT_EQ(standard.mode, ReportConfig::Mode::Standard);
  const std::vector<SceneSize> paper{SceneSize::S, SceneSize::M, SceneSize::L};
  EXPECT_EQ(standard.table_sizes("quadruped"), paper);
  std::vector<std::string> paper_models;
  for (SceneSize size : paper) paper_models.push_back(paper_model_of(size));
  EXPECT_EQ(paper_models, (std::vector<std::string>{"bunny", "horse", "dragon"}));
  EXPECT_TRUE(standard.comparison_tables(SceneSize::S));
  EXPECT_FALSE(standard.comparison_tables(SceneSize::M));
  EXPECT_FALSE(standard.comparison_tables(SceneSize::L));
  EXPECT_FALSE(standard.jacobi_table(SceneSize::L));
  ReportConfig with_models;
  with_models.models_dir = "models";  // the horse's and dragon's Jacobi rows: issue 36's targets
  EXPECT_TRUE(with_models.jacobi_table(SceneSize::M));
  EXPECT_TRUE(with_models.jacobi_table(SceneSize::L));
  EXPECT_FALSE(with_models.comparison_tables(SceneSize::L));
  // Every procedural stability scene but quadruped-stretched (stability_scene_full_only), which
  // --only still runs and --full keeps.
  std::vector<std::string> every = stability_scene_ids(false), standard_scenes = every;
  std::erase(standard_scenes, std::string("quadruped-stretched"));
  EXPECT_EQ(standard.stability_scenes(), standard_scenes);
  ReportConfig only_it;
  only_it.only = "quadruped-stretched";
  EXPECT_EQ(only_it.stability_scenes(), std::vector<std::string>{"quadruped-stretched"});
  ReportConfig full;
  full.mode = ReportConfig::Mode::Full;
  EXPECT_EQ(full.table_sizes("quadruped"), paper);
  EXPECT_TRUE(full.comparison_tables(SceneSize::L));
  EXPECT_GT(full.stability_hold(), standard.stability_hold());
  EXPECT_EQ(full.stability_scenes(), every);
  ReportConfig quick;
  quick.mode = ReportConfig::Mode::Quick;
  EXPECT_EQ(quick.table_sizes("quadruped"), std::vector<SceneSize>{SceneSize::Small});
}

/// Each line of a section names its unit, its number of how many and, once a unit has finished,
/// the minutes left at the rate so far (issue 38's "stability 14/96, about 3 min left").
TEST(Report, SectionProgressCountsUnitsAndEstimatesTheTimeLeft) {
  SectionProgress progress(nullptr, "tables", 3);
  EXPECT_EQ(progress.begin("quadruped-11k"), "report: tables 1/3: quadruped-11k");
  progress.finish();
  const std::string second = progress.begin("quadruped-34k");
  EXPECT_EQ(second.rfind("report: tables 2/3: quadruped-34k (about ", 0), 0u) << second;
  EXPECT_NE(second.find(" min left)"), std::string::npos) << second;
}

TEST(Report, BadOptionsExitTwo) {
  EXPECT_EQ(run_cli("report --quick --smoke --out x").exit_code, 2);
  EXPECT_EQ(run_cli("report --full --quick --out x").exit_code, 2);
  EXPECT_EQ(run_cli("report --tables-only --stability-only --out x").exit_code, 2);
  TempDir empty;
  const auto r = run_cli("report --models '" + empty.path().string() + "' --out x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bunny_L0.stl"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace corofem

namespace corofem {
namespace {

TEST(ReportOracles, ACheckWithNoOracleWiredIsRefusedNotRecorded) {
  // lib/ links no oracle: the executable wires them (cli/main.cpp). The gates' binary wires
  // none, so a check asked for here must refuse, naming the oracle, and run once wired.
  try {
    report_oracles("galerkin");
    ADD_FAILURE() << "an oracle nobody wired was handed out";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'galerkin' is not wired"), std::string::npos) << e.what();
  }
  set_report_oracles(
      {.direct_solve = reference::cholmod_solve, .galerkin = reference::eigen_galerkin});
  Eigen::SparseMatrix<double> a(2, 2);
  a.insert(0, 0) = 4;
  a.insert(1, 1) = 2;
  const Eigen::VectorXd x = report_oracles("direct_solve").direct_solve(a, Eigen::Vector2d(8, 2));
  EXPECT_DOUBLE_EQ(x[0], 2);
  EXPECT_DOUBLE_EQ(x[1], 1);
  set_report_oracles({});  // as the binary was
}

}  // namespace
}  // namespace corofem
