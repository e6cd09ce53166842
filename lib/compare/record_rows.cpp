#include "compare/record_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>

#include "core/errors.hpp"

namespace corofem {
namespace {

using json = nlohmann::json;

/// FNV-1a of the scene's canonical text (nlohmann sorts object keys): equal scenes, equal digest.
std::string digest(const json& scene) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : scene.dump()) h = (h ^ c) * 1099511628211ULL;
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

int threads_of(const json& record) {
  const json& context = record.value("context", json::object());
  return context.is_object() ? context.value("threads_used", 1) : 1;
}

/// Collects rows; a key met again (another record of the same case) becomes another run.
class RowSink {
 public:
  RowSink(RecordSet& set, std::string file) : set_(set), file_(std::move(file)) {}

  void timed(const std::string& case_name, const std::string& scene, int threads,
             const std::string& quantity, std::vector<double> samples, const std::string& row) {
    for (double v : samples)
      if (!std::isfinite(v) || v < 0)
        throw InputError(file_ + ": " + row + ": " + quantity +
                         " has a time that is negative or not finite");
    // A phase that took no measurable time (under the records' 0.1 us) carries no ratio.
    samples.erase(std::remove(samples.begin(), samples.end(), 0.0), samples.end());
    if (samples.empty()) return;
    row_for(case_name, scene, threads, quantity, RowKind::Timed, row).runs.push_back(samples);
  }
  void value(const std::string& case_name, const std::string& scene, int threads,
             const std::string& quantity, RowKind kind, const json& v, const std::string& row) {
    if (v.is_null()) return;
    if (!v.is_number()) throw InputError(file_ + ": " + row + ": " + quantity + " is not a number");
    row_for(case_name, scene, threads, quantity, kind, row).values.push_back(v.get<double>());
  }
  void count(const std::string& case_name, const std::string& scene, int threads,
             const std::string& quantity, const json& v, const std::string& provenance,
             const std::string& row) {
    if (!v.is_number() || !(v.get<double>() >= 0))
      throw InputError(file_ + ": " + row + ": " + quantity + " is not a count");
    RecordRow& r = row_for(case_name, scene, threads, quantity, RowKind::Count, row);
    if (!r.values.empty() && r.provenance != provenance)
      throw InputError(file_ + ": " + row + ": " + quantity + " was counted otherwise than in " +
                       r.source + " (the repetitions of one case must be counted alike)");
    r.provenance = provenance;
    r.values.push_back(v.get<double>());
  }
  void field(const std::string& case_name, const std::string& scene, int threads,
             const std::string& quantity, std::vector<double> values, const std::string& row) {
    RecordRow& r = row_for(case_name, scene, threads, quantity, RowKind::Field, row);
    if (r.field.empty()) r.field = std::move(values);
  }

 private:
  RecordRow& row_for(const std::string& case_name, const std::string& scene, int threads,
                     const std::string& quantity, RowKind kind, const std::string& row) {
    RecordRow key_row;
    key_row.case_name = case_name;
    key_row.threads = threads;
    key_row.quantity = quantity;
    const std::string key = key_row.key();
    for (RecordRow& r : set_.rows)
      if (r.key() == key) {
        if (r.scene_digest != scene)
          throw InputError(file_ + ": " + row + ": case '" + case_name +
                           "' was run on another scene than in " + r.source +
                           " (their repetitions must be of one scene)");
        return r;
      }
    key_row.scene_digest = scene;
    key_row.kind = kind;
    key_row.source = file_ + ": " + row;
    set_.rows.push_back(std::move(key_row));
    return set_.rows.back();
  }

  RecordSet& set_;
  std::string file_;
};

std::vector<double> numbers(const json& array, const std::string& what) {
  if (!array.is_array()) throw InputError(what + " is not an array");
  std::vector<double> out;
  for (const json& v : array) {
    if (!v.is_number()) throw InputError(what + " holds a value that is not a number");
    out.push_back(v.get<double>());
  }
  return out;
}

/// A run record's counters (iterations, steps, the hierarchy's sizes) and its static residual.
void run_counter_rows(const json& r, const std::string& name, const std::string& scene, int threads,
                      RowSink& sink) {
  for (const char* counter : {"linear_iterations", "iterations", "steps", "inverted_max"})
    if (r.contains(counter))
      sink.value(name, scene, threads, counter, RowKind::Counter, r[counter], counter);
  // The hierarchy's size: vertices and nonzero 3x3 blocks per level.
  if (r.contains("multigrid") && r["multigrid"].is_object())
    for (const json& level : r["multigrid"].value("levels", json::array()))
      for (const char* what : {"vertices", "blocks"})
        if (level.contains(what))
          sink.value(name, scene, threads,
                     "level " + std::to_string(level.value("level", 0)) + " " + what,
                     RowKind::Counter, level[what], "multigrid.levels");
  if (r.value("analysis", json::object()).value("type", "") == "static" && r.contains("residual"))
    sink.value(name, scene, threads, "equilibrium residual", RowKind::Accuracy, r["residual"],
               "residual");
}

/// A run record's times: per step and phase (dynamic), and the whole run's set-up and total.
void run_time_rows(const json& r, const std::string& file, const std::string& name,
                   const std::string& scene, int threads, RowSink& sink) {
  if (r.contains("step_samples_ms")) {
    for (const auto& [phase, samples] : r["step_samples_ms"].items())
      sink.timed(name, scene, threads, phase, numbers(samples, file + ": step_samples_ms." + phase),
                 "step_samples_ms");
  } else if (r.value("steps", 0) > 0 &&
             r.value("analysis", json::object()).value("type", "") == "dynamic") {
    // A record from before the samples were kept: each phase's mean over the run's steps, one
    // sample per run (ci/bench-gate's repetitions still give a test over runs).
    for (const auto& [phase, total] : r["timings_ms"].items())
      if (phase != "setup" && phase != "total" && total.is_number())
        sink.timed(name, scene, threads, phase, {total.get<double>() / r["steps"].get<double>()},
                   "timings_ms (per-step means: the record keeps no samples)");
  }
  for (const char* total : {"setup", "total"})
    if (r["timings_ms"].contains(total))
      sink.timed(name, scene, threads, std::string("run ") + total,
                 {r["timings_ms"][total].get<double>()}, "timings_ms");
}

/// What made a record's phase counts, as canonical JSON (RecordRow::provenance).
std::string count_provenance(const json& r, const json& counts) {
  json p = json::object();
  for (const char* key : {"source", "tool", "events", "simulated_caches", "processor_seen"})
    p[key] = counts.value(key, json());
  const json& context = r.value("context", json::object());
  for (const char* key : {"compiler", "flags", "build_type", "block_kernels"})
    p[key] = context.is_object() ? context.value(key, json()) : json();
  return p.dump();
}

/// A counted run's `phase_counts`: each section's instructions and misses, and the stretches
/// between the sections.
void phase_count_rows(const json& r, const json& counts, const std::string& name,
                      const std::string& scene, RowSink& sink) {
  const std::string provenance = count_provenance(r, counts);
  const int threads = counts.value("threads", 1);
  static const std::pair<const char*, const char*> kEvents[] = {
      {"instructions", "instructions"}, {"d1_misses", "D1 misses"}, {"ll_misses", "LL misses"}};
  const auto add = [&](const std::string& section, const json& c, const std::string& row) {
    for (const auto& [key, label] : kEvents)
      if (c.contains(key))
        sink.count(name, scene, threads, section + " " + label, c[key], provenance, row);
  };
  for (const auto& [section, c] : counts["sections"].items())
    add(section, c, "phase_counts.sections." + section);
  if (counts.contains("outside")) add("between phases", counts["outside"], "phase_counts.outside");
}

/// `corofem run`: per-step phase times (dynamic), whole-run times, counters, phase counts, the
/// final field. A run counted under callgrind gives no timed rows: its times are valgrind's.
void run_rows(const json& r, const std::string& file, RowSink& sink) {
  if (!r.contains("scene") || !r.contains("timings_ms"))
    throw InputError(file + ": a corofem run record without scene or timings_ms");
  // The scene file's name, not its path: records made in two checkouts pair (the digest still
  // refuses two different scenes of one name).
  const std::string name =
      "run " +
      std::filesystem::path(r.value("scene_file", std::string("scene"))).filename().string();
  const std::string scene = digest(r["scene"]);
  const int threads = threads_of(r);
  const json counts = r.value("phase_counts", json());
  const bool counted = counts.is_object() && counts.value("sections", json()).is_object();
  if (counted) phase_count_rows(r, counts, name, scene, sink);
  if (!counted || counts.value("source", std::string()) != "callgrind")
    run_time_rows(r, file, name, scene, threads, sink);
  run_counter_rows(r, name, scene, threads, sink);
  if (r.contains("displacement") && r["displacement"].is_array()) {
    std::vector<double> u;
    for (const json& v : r["displacement"])
      for (const json& c : v) u.push_back(c.is_number() ? c.get<double>() : NAN);
    sink.field(name, scene, threads, "displacement", std::move(u), "displacement");
  }
}

/// A Table 1 run: its per-step samples per phase, or its medians where it kept none (a record
/// from before the samples were kept), and its roofline's bytes and flops.
void table1_run_rows(const json& run, const std::string& name, const std::string& scene,
                     int threads, const std::string& row, RowSink& sink) {
  if (run.contains("samples_ms")) {
    for (const auto& [phase, samples] : run["samples_ms"].items())
      sink.timed(name, scene, threads, phase, numbers(samples, row + ".samples_ms." + phase), row);
  } else {
    const json& medians = run.contains("phases_ms") ? run["phases_ms"] : run;
    for (const char* phase : {"rotate", "assemble", "update", "solve", "step"})
      if (medians.contains(phase) && medians[phase].is_number())
        sink.timed(name, scene, threads, phase, {medians[phase].get<double>()}, row);
  }
  if (run.contains("linear_iterations"))
    sink.value(name, scene, threads, "linear_iterations", RowKind::Counter,
               run["linear_iterations"], row);
  if (run.contains("roofline") && run["roofline"].is_object()) {
    // Held here: items() keeps a reference, which a temporary of value() would leave dangling.
    const json phases = run["roofline"].value("phases", json::object());
    for (const auto& [phase, t] : phases.items())
      for (const char* what : {"bytes", "flops"})
        if (t.contains(what))
          sink.value(name, scene, threads, phase + " " + what, RowKind::Counter, t[what], row);
  }
}

void tables_rows(const json& r, RowSink& sink) {
  const int threads = threads_of(r);
  for (const json& row : r.value("table1", json::array())) {
    if (!row.value("completed", false)) continue;
    const std::string model = row.value("model", std::string("?"));
    const std::string where = "table1 row '" + model + "'";
    const std::string name = "table1 " + model;
    const std::string scene = digest(row.value("scene", json(model)));
    table1_run_rows(row, name, scene, threads, where, sink);
    if (threads != 1 && row.contains("one_thread"))
      table1_run_rows(row["one_thread"], name, scene, 1, where + ".one_thread", sink);
  }
  for (const json& row : r.value("multigrid", json::array())) {
    if (!row.value("completed", false)) continue;
    const std::string model = row.value("model", std::string("?"));
    const std::string name = "multigrid " + model, where = "multigrid row '" + model + "'";
    for (const char* counter : {"mgpcg_iterations", "vcycles"})
      if (row.contains(counter))
        sink.value(name, model, threads, counter, RowKind::Counter, row[counter], where);
    const json& levels = row.value("level_vertices", json::array());
    for (std::size_t l = 0; l < levels.size(); ++l)
      sink.value(name, model, threads, "level " + std::to_string(l) + " vertices", RowKind::Counter,
                 levels[l], where);
  }
  for (const json& row : r.value("verification", json::array())) {
    const std::string model = row.value("model", std::string("?"));
    for (const json& check : row.value("checks", json::array()))
      sink.value("verification " + model, model, threads, check.value("quantity", "?"),
                 RowKind::Accuracy, check.value("largest", json(nullptr)),
                 "verification row '" + model + "'");
  }
}

void speed_accuracy_rows(const json& r, RowSink& sink) {
  const int threads = threads_of(r);
  for (const json& scene : r.value("scenes", json::array())) {
    if (!scene.value("completed", false)) continue;
    const std::string model = scene.value("model", std::string("?"));
    for (const json& p : scene.value("points", json::array())) {
      if (!p.value("completed", false)) continue;
      const std::string label = p.value("label", std::string("?"));
      const std::string name = "speed-accuracy " + model + " " + label;
      const std::string where = "speed_accuracy point '" + model + " " + label + "'";
      const std::string setting = digest(p.value("setting", json(label)));
      if (p.contains("step_samples_ms"))
        sink.timed(name, setting, threads, "step",
                   numbers(p["step_samples_ms"], where + ".step_samples_ms"), where);
      else if (p.contains("time_per_step_ms"))
        sink.timed(name, setting, threads, "step", {p["time_per_step_ms"].get<double>()}, where);
      if (p.contains("iterations_per_step"))
        sink.value(name, setting, threads, "iterations_per_step", RowKind::Counter,
                   p["iterations_per_step"], where);
      if (p.contains("rel_error") && !p.value("is_reference", false))
        sink.value(name, setting, threads, "rel_error", RowKind::Accuracy, p["rel_error"], where);
    }
  }
}

void cache_profile_rows(const json& r, RowSink& sink) {
  const std::string name = "cache-profile " + r.value("model", std::string("?"));
  // Its settings are its scene: profiles of other caches, updates or sizes do not pair.
  json settings = json::object();
  for (const char* key : {"tool", "tool_note", "updates", "threads", "fine_blocks"})
    settings[key] = r.value(key, json(nullptr));
  const std::string scene = digest(settings);
  for (const json& result : r.value("results", json::array())) {
    const std::string method = result.value("method", std::string("?"));
    for (const char* counter :
         {"instructions_per_update", "d1_misses_per_update", "ll_misses_per_update"})
      if (result.contains(counter))
        sink.value(name, scene, 1, method + " " + counter, RowKind::Counter, result[counter],
                   "results '" + method + "'");
  }
}

/// Google Benchmark's JSON: each repetition of a benchmark is one run of one sample (its
/// real_time). Its aggregates (mean, median, stddev) are summaries of those repetitions, not more
/// of them: left out where the repetitions are there, and where only they are (a file written with
/// --benchmark_report_aggregates_only), the median is the benchmark's one sample.
void benchmark_rows(const json& r, const std::string& file, RowSink& sink) {
  static const std::map<std::string, double> kMs = {
      {"ns", 1e-6}, {"us", 1e-3}, {"ms", 1.0}, {"s", 1e3}};
  const int threads = r.value("context", json::object()).value("threads_used", 1);
  std::set<std::string> repeated;
  for (const json& b : r["benchmarks"])
    if (b.value("run_type", std::string("iteration")) == "iteration")
      repeated.insert(b.value("run_name", b.value("name", std::string("?"))));
  for (const json& b : r["benchmarks"]) {
    const bool median_alone = b.value("run_type", std::string()) == "aggregate" &&
                              b.value("aggregate_name", std::string()) == "median" &&
                              !repeated.count(b.value("run_name", std::string("?")));
    if (b.value("run_type", std::string("iteration")) != "iteration" && !median_alone) continue;
    if (b.contains("error_occurred") && b["error_occurred"].get<bool>()) continue;
    const std::string name = b.value("run_name", b.value("name", std::string("?")));
    const std::string unit = b.value("time_unit", std::string("ns"));
    if (!kMs.count(unit) || !b.contains("real_time") || !b["real_time"].is_number())
      throw InputError(file + ": benchmark '" + name + "' has no real_time in a known unit");
    sink.timed("bench " + name, "benchmark", b.value("threads", threads), "real_time",
               {b["real_time"].get<double>() * kMs.at(unit)}, "benchmark '" + name + "'");
  }
}

json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot be read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path.string() + ": not JSON (" + e.what() + ")");
  }
}

bool knows(const json& r) {
  if (!r.is_object()) return false;
  const std::string producer = r.value("producer", std::string());
  return producer == "corofem run" || producer == "corofem report (tables)" ||
         producer == "bench/count_phases.py" || r.contains("benchmarks") ||
         (r.contains("scenes") && r.contains("error_definitions")) ||
         r.value("tool", std::string()) == "cachegrind";
}

}  // namespace

std::string RecordRow::key() const {
  return case_name + " | " + std::to_string(threads) + (threads == 1 ? " thread" : " threads") +
         " | " + quantity;
}

void add_record_rows(const json& r, const std::string& file, RecordSet& set) {
  RowSink sink(set, file);
  set.contexts[file] = r.is_object() ? r.value("context", json(nullptr)) : json(nullptr);
  const std::string producer = r.value("producer", std::string());
  try {
    if (producer == "corofem run")
      run_rows(r, file, sink);
    else if (producer == "bench/count_phases.py")  // counted runs, one record each
      for (const json& record : r.at("records")) {
        set.contexts[file] = record.value("context", json(nullptr));
        run_rows(record, file, sink);
      }
    else if (producer == "corofem report (tables)")
      tables_rows(r, sink);
    else if (r.contains("benchmarks"))
      benchmark_rows(r, file, sink);
    else if (r.contains("scenes") && r.contains("error_definitions"))
      speed_accuracy_rows(r, sink);
    else if (r.value("tool", std::string()) == "cachegrind")
      cache_profile_rows(r, sink);
    else
      throw InputError(file +
                       ": not a record corofem compare knows (a corofem run record, a report's "
                       "tables.json, speed_accuracy.json or cache_profile.json, "
                       "bench/count_phases.py's counts, or Google Benchmark JSON)");
  } catch (const json::exception& e) {
    throw InputError(file + ": a malformed field (" + e.what() + ")");
  }
}

RecordSet read_records(const std::filesystem::path& path) {
  RecordSet set;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(path, ec))
      if (entry.is_regular_file() && entry.path().extension() == ".json")
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      const json r = read_json(file);
      if (knows(r)) add_record_rows(r, file.string(), set);
    }
    if (set.rows.empty())
      throw InputError(path.string() + ": a folder with no record corofem compare knows");
  } else {
    if (!std::filesystem::exists(path, ec)) throw InputError(path.string() + ": no such file");
    add_record_rows(read_json(path), path.string(), set);
  }
  return set;
}

}  // namespace corofem
