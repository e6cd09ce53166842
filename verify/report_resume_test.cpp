// `corofem report --resume`: a report killed part-way (SIGKILL, which no handler sees) and resumed
// ends with the records of a run that was never killed, but for times; what it had finished is
// kept, not run again. The report runs the smoke report's bar-twist stability study (seven units,
// one per rotation method) beside the other sections, which have no work for that name and are
// written at once: so the kill finds sections written and a section part-way.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "test_support.hpp"

namespace corofem {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::read_text;
using test::run_cli;
using test::TempDir;

const std::string kReport = "report --smoke --threads 2 --only bar-twist --no-render";
constexpr const char* kRecords[] = {"tables.json", "speed_accuracy.json", "stability.json",
                                    "stability_frames.json", "model_accuracy.json"};

/// Whether a leaf at `path` (its keys, outermost first) holds a time or what derives from times:
/// phase times (*_ms, any value under a *_ms object, a one-thread column's phases), rates, roofs
/// and the ratios to them, the choices made by time (Pareto fronts, the cheapest setting, a
/// roofline's bound), the date, and the cores' handoff time (core_to_core_ns).
bool is_time(const std::vector<std::string>& path) {
  static const std::vector<std::string> phases = {"rotate", "assemble", "forces", "system",
                                                  "update", "solve",    "checks", "step"};
  for (std::size_t k = 0; k < path.size(); ++k) {
    const std::string& key = path[k];
    if (key.ends_with("_ms") || key.ends_with("_s") || key.ends_with("_ns") || key == "tps" ||
        key.ends_with("_tps") || key.find("GBps") != std::string::npos ||
        key.find("gflops") != std::string::npos || key.find("over_") != std::string::npos ||
        key.find("speedup") != std::string::npos || key == "bound" || key == "pareto" ||
        key == "cheapest_meeting_target" || key == "date")
      return true;
    if (k > 0 && path[k - 1] == "one_thread" &&
        std::find(phases.begin(), phases.end(), key) != phases.end())
      return true;
  }
  return false;
}

/// Every difference between two records outside times, as "path: a vs b".
void differences(const json& a, const json& b, std::vector<std::string>& path,
                 std::vector<std::string>& out) {
  std::string where;
  for (const std::string& key : path) where += "/" + key;
  if (is_time(path)) return;
  if (a.type() != b.type()) {
    out.push_back(where + ": " + a.dump().substr(0, 80) + " vs " + b.dump().substr(0, 80));
  } else if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      path.push_back(key);
      differences(value, b.contains(key) ? b[key] : json(), path, out);
      path.pop_back();
    }
    for (const auto& [key, value] : b.items())
      if (!a.contains(key) && !is_time(path)) out.push_back(where + "/" + key + ": only in one");
  } else if (a.is_array()) {
    if (a.size() != b.size()) {
      out.push_back(where + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) +
                    " entries");
      return;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
      path.push_back("[]");
      differences(a[i], b[i], path, out);
      path.pop_back();
    }
  } else if (a != b) {
    out.push_back(where + ": " + a.dump() + " vs " + b.dump());
  }
}

/// Whole lines of a file (what the checkpoint has kept), 0 if there is none.
int whole_lines(const fs::path& file) {
  std::ifstream in(file);
  int lines = 0;
  for (std::string line; std::getline(in, line) && !in.eof();) ++lines;
  return lines;
}

/// Starts `corofem REPORT --out dir` and kills it (SIGKILL) once the stability study has kept
/// `units` units and before it has written its record. Returns whether it was caught so.
bool kill_part_way(const fs::path& dir, int units) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string command = "exec '" + std::string(COROFEM_CLI) + "' " + kReport + " --out '" +
                                dir.string() + "' > /dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path kept = dir / ".resume" / "stability.jsonl";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  bool caught = false;
  while (std::chrono::steady_clock::now() < deadline) {
    if (whole_lines(kept) >= units) {
      caught = !fs::exists(dir / "stability.json");
      break;
    }
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // it ended before
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  return caught;
}

TEST(ReportResume, AReportKilledPartWayAndResumedWritesTheUninterruptedRecords) {
  TempDir dir;
  const fs::path whole = dir / "whole", killed = dir / "killed";
  const auto uninterrupted = run_cli(kReport + " --out '" + whole.string() + "'");
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.err;
  EXPECT_FALSE(fs::exists(whole / ".resume")) << "a report that ends leaves no checkpoint";

  ASSERT_TRUE(kill_part_way(killed, 2)) << "the kill did not land inside the stability study";
  EXPECT_TRUE(fs::exists(killed / "tables.json"));
  EXPECT_FALSE(fs::exists(killed / "model_accuracy.json"));
  // Other options than the killed run's are refused, naming what differs.
  const auto other = run_cli(
      "report --smoke --threads 1 --only bar-twist --no-render --resume "
      "--out '" +
      killed.string() + "'");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("threads 2 then, 1 now"), std::string::npos) << other.err;

  const auto resumed = run_cli(kReport + " --resume --out '" + killed.string() + "'");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("tables.json kept from the interrupted run"), std::string::npos)
      << resumed.err;
  EXPECT_NE(resumed.err.find(": kept from the interrupted run"), std::string::npos)
      << "no stability unit was kept:\n"
      << resumed.err;
  EXPECT_FALSE(fs::exists(killed / ".resume"));
  for (const char* file : kRecords) {
    std::vector<std::string> path, found;
    differences(json::parse(read_text(whole / file)), json::parse(read_text(killed / file)), path,
                found);
    std::string list;
    for (const std::string& d : found) list += "\n  " + d;
    EXPECT_TRUE(found.empty()) << file << " differs from the uninterrupted run's:" << list;
  }
  // Nothing left to resume once it ran to its end.
  const auto again = run_cli(kReport + " --resume --out '" + killed.string() + "'");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("has no report to resume"), std::string::npos) << again.err;
}

TEST(ReportResume, TheComparisonOfRecordsSeesADifferenceOutsideTimes) {
  // The check above is only as good as its comparison: a changed iteration count or status is
  // found, a changed time is not.
  const json a = {{"runs", {{{"status", "stable"}, {"iterations", 4}, {"step_ms", 1.0}}}},
                  {"one_thread", {{"solve", 2.0}}}};
  json b = a;
  b["runs"][0]["step_ms"] = 3.0;
  b["one_thread"]["solve"] = 5.0;
  std::vector<std::string> path, found;
  differences(a, b, path, found);
  EXPECT_TRUE(found.empty());
  b["runs"][0]["status"] = "flutter";
  b["runs"][0]["iterations"] = 5;
  differences(a, b, path, found);
  EXPECT_EQ(found.size(), 2u);
}

}  // namespace
}  // namespace corofem
