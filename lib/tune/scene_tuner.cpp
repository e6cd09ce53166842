#include "tune/scene_tuner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/statistics.hpp"
#include "io/run_context.hpp"
#include "report/section_progress.hpp"
#include "tune/candidate_run.hpp"

namespace corofem {
using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A setting that ran: where in the search, which values, what it cost and missed by.
struct Measured {
  std::string stage;  ///< reference | given | screening | combination | re-run
  std::vector<int> setting{};
  CandidateRun run{};
  double error = kNaN;  ///< against the reference, the reference's own error not included
  /// Against the base (the scene's resolution, the reference's other settings): what a setting
  /// other than the resolution costs in accuracy on its own (= error where base = reference).
  double base_error = kNaN;
  double predicted_error = kNaN, predicted_cost_ms = kNaN;  ///< combinations
};

/// The reference's own error from the resolutions screened below it (Richardson).
struct ReferenceError {
  double value = 0;
  json record;
};

class Tuner {
 public:
  Tuner(const json& raw, std::filesystem::path base_dir, std::string name,
        const TuneOptions& options)
      : raw_(raw),
        base_dir_(std::move(base_dir)),
        name_(std::move(name)),
        options_(options),
        scene_(parse_scene(raw, base_dir_, name_)),
        quantity_(options.quantity),
        deadline_(start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(60 * options.budget_minutes))) {
    axes_ = tune_axes(scene_, raw_, options_.axes, resolution_note_);
    for (const TuneAxis& axis : axes_) reference_setting_.push_back(axis.reference);
    int units = 3;  // reference, the scene as given, the re-run
    for (const TuneAxis& axis : axes_) units += static_cast<int>(axis.values.size()) - 1;
    progress_.emplace(options_.progress, "run", units + options_.combinations, "tune");
  }

  TuneOutcome run();

  /// A screened value's own error: the resolution's against the reference, another axis's
  /// against the base.
  static double own_error(std::size_t axis, const Measured& m) {
    return axis == 0 ? m.error : m.base_error;
  }

 private:
  bool out_of_time() const { return std::chrono::steady_clock::now() > deadline_; }
  std::string label_of(const std::vector<int>& setting) const;
  json setting_json(const std::vector<int>& setting) const;
  /// Runs a setting (or, with `scene`, that scene) and measures it against the reference.
  Measured& measure(const std::string& stage, const std::vector<int>& setting,
                    const std::optional<json>& scene = std::nullopt);
  /// A completed run's error against the base (its error where the base is the reference).
  double against_base(const Measured& m) const {
    return base_index_ == 0
               ? m.error
               : quantity_error(quantity_, m.run.state, measured_[base_index_].run.state);
  }
  /// The run of the base (the reference for the resolution axis) with axis `axis` at `value`.
  const Measured* screened(std::size_t axis, int value) const;
  const std::vector<int>& origin(std::size_t axis) const {
    return axis == 0 ? reference_setting_ : base_setting_;
  }
  void screen_axis(std::size_t a, double allowance);
  ReferenceError reference_error() const;
  void combine(double allowance);
  json candidate_json(const Measured& m, double reference_error) const;
  TuneOutcome answer(Measured choice, const ReferenceError& e_ref, const std::string& status,
                     const std::string& reason);
  /// The record's account of the search: what was tuned against what, the axes, the runs.
  json search_record(const ReferenceError& e_ref) const;
  /// Every candidate measured, those completed marked on the Pareto front or not.
  json candidates_record(double reference_error) const;

  const json& raw_;
  std::filesystem::path base_dir_;
  std::string name_;
  TuneOptions options_;
  Scene scene_;
  QuantitySpec quantity_;
  std::vector<TuneAxis> axes_;
  std::string resolution_note_;
  std::vector<int> reference_setting_;
  /// The other axes are screened at the scene's own resolution (a finer reference would make
  /// every screening run cost as much as the reference): the reference's settings there.
  std::vector<int> base_setting_;
  int base_index_ = -1;               ///< in measured_
  std::vector<Measured> measured_;    ///< [0]: the reference
  int given_index_ = -1;              ///< in measured_: the scene as the user wrote it
  std::vector<std::string> skipped_;  ///< values the search left out, and why
  bool budget_spent_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), deadline_;
  std::optional<SectionProgress> progress_;
};

std::string Tuner::label_of(const std::vector<int>& setting) const {
  std::string label;
  for (std::size_t a = 0; a < axes_.size(); ++a)
    if (setting[a] != reference_setting_[a])
      label += (label.empty() ? "" : ", ") + axes_[a].values[setting[a]].label;
  return label.empty() ? "the reference" : label;
}

json Tuner::setting_json(const std::vector<int>& setting) const {
  json j = json::object();
  for (std::size_t a = 0; a < axes_.size(); ++a)
    j[axes_[a].name] = axes_[a].values[setting[a]].label;
  return j;
}

Measured& Tuner::measure(const std::string& stage, const std::vector<int>& setting,
                         const std::optional<json>& scene) {
  const std::string what =
      stage + ": " + (stage == "given" ? "the scene as given" : label_of(setting));
  const std::string prefix = progress_->begin(what);
  Measured m{.stage = stage, .setting = setting};
  const std::optional<json> s = scene ? scene : apply_setting(raw_, axes_, setting);
  m.run = run_candidate(*s, base_dir_, name_, time_factor(axes_, setting));
  if (m.run.completed && !measured_.empty())
    m.error = quantity_error(quantity_, m.run.state, measured_.front().run.state);
  if (m.run.completed && measured_.empty()) m.error = 0;
  if (m.run.completed && base_index_ >= 0) m.base_error = against_base(m);
  progress_->finish();
  if (options_.progress)
    *options_.progress << prefix << ": "
                       << (m.run.completed ? "error " + general_number(m.error) + ", " +
                                                 general_number(m.run.cost_ms) + " ms"
                                           : "failed: " + m.run.failure)
                       << "\n";
  measured_.push_back(std::move(m));
  return measured_.back();
}

const Measured* Tuner::screened(std::size_t axis, int value) const {
  for (const Measured& m : measured_) {
    if (m.stage != "screening" && m.stage != "reference") continue;
    bool match = m.setting[axis] == value;
    for (std::size_t a = 0; a < axes_.size() && match; ++a)
      if (a != axis) match = m.setting[a] == origin(axis)[a];
    if (match) return &m;
  }
  return nullptr;
}

/// Every value of axis `a` alone from the reference; an ordered family stops at its first miss.
void Tuner::screen_axis(std::size_t a, double allowance) {
  const TuneAxis& axis = axes_[a];
  std::vector<std::string> stopped;
  for (int i = 0; i < static_cast<int>(axis.values.size()); ++i) {
    if (i == origin(a)[a] || screened(a, i)) continue;
    const AxisValue& value = axis.values[i];
    if (std::find(stopped.begin(), stopped.end(), value.family) != stopped.end()) {
      skipped_.push_back(value.label + ": a more accurate value of its family missed the target");
      continue;
    }
    if (out_of_time()) {
      budget_spent_ = true;
      skipped_.push_back(value.label + ": the budget was spent");
      continue;
    }
    std::vector<int> setting = origin(a);
    setting[a] = i;
    const Measured& m = measure("screening", setting);
    if (!m.run.completed || !(own_error(a, m) <= allowance)) stopped.push_back(value.family);
  }
}

ReferenceError Tuner::reference_error() const {
  ReferenceError e;
  const std::size_t resolution = 0;  // tune_axes puts it first
  const Measured* fine = screened(resolution, 0);
  const Measured* coarse = screened(resolution, 1);
  if (!options_.axes.resolution_free) {
    e.record = {
        {"value", 0},
        {"method", "not counted: --resolution fixed, errors are against the scene's own mesh"}};
    return e;
  }
  if (!coarse || !coarse->run.completed) {
    e.record = {{"value", nullptr},
                {"method", "not estimated: " + (resolution_note_.empty()
                                                    ? std::string("no coarser resolution ran")
                                                    : resolution_note_)}};
    return e;
  }
  // |Q_h - Q| ~ |Q_h - Q_rh| / (r^p - 1), r the ratio of element sizes from the tet counts.
  const double d1 = coarse->error;
  const double r = std::cbrt(static_cast<double>(fine->run.tets) / coarse->run.tets);
  double order = 1, observed = kNaN;
  const Measured* coarser = screened(resolution, 2);
  if (coarser && coarser->run.completed) {
    const double d2 = quantity_error(quantity_, coarser->run.state, coarse->run.state);
    const double r2 = std::cbrt(static_cast<double>(coarse->run.tets) / coarser->run.tets);
    if (d1 > 0 && d2 > d1) observed = std::log(d2 / d1) / std::log(0.5 * (r + r2));
  }
  // The observed order only where it is plausible for linear tets (1..2); else 1, which
  // overestimates the error of a method that converges faster.
  // A surface's coarser resolutions also change the body (simplified): not the same sequence.
  const bool same_body = scene_.mesh.kind != MeshSpec::Kind::Surface;
  if (same_body && std::isfinite(observed) && observed >= 1) order = std::min(observed, 2.0);
  e.value = d1 / (std::pow(r, order) - 1);
  e.record = {{"value", e.value},
              {"method", "Richardson over the reference and the next coarser resolution"},
              {"tets", {fine->run.tets, coarse->run.tets}},
              {"difference", d1},
              {"size_ratio", r},
              {"observed_order", std::isfinite(observed) ? json(observed) : json(nullptr)},
              {"order_used", order}};
  return e;
}

/// The values that met the target alone, combined: the cheapest predicted first, measured.
void Tuner::combine(double allowance) {
  std::vector<std::vector<int>> admissible(axes_.size());
  for (std::size_t a = 0; a < axes_.size(); ++a)
    for (int i = 0; i < static_cast<int>(axes_[a].values.size()); ++i)
      if (const Measured* m = screened(a, i);
          m && m->run.completed && own_error(a, *m) <= allowance)
        admissible[a].push_back(i);
  // Costs relative to each axis's origin: the resolution's to the reference, the others' to the
  // base; the prediction starts from the reference's cost.
  const double reference_cost = measured_.front().run.cost_ms;
  const double base_cost = measured_[base_index_].run.cost_ms;
  struct Predicted {
    std::vector<int> setting;
    double error, cost;
  };
  std::vector<Predicted> predicted;
  std::vector<std::size_t> index(axes_.size(), 0);
  while (true) {
    Predicted p{{}, 0, reference_cost};
    for (std::size_t a = 0; a < axes_.size(); ++a) {
      const int v = admissible[a][index[a]];
      p.setting.push_back(v);
      const Measured* m = screened(a, v);
      // Errors of independent settings add at most (triangle inequality).
      p.error += own_error(a, *m);
      p.cost *= m->run.cost_ms / (a == 0 ? reference_cost : base_cost);
    }
    const bool measured = std::any_of(measured_.begin(), measured_.end(), [&](const Measured& m) {
      return m.stage != "given" && m.setting == p.setting;
    });
    if (!measured && p.error <= allowance) predicted.push_back(std::move(p));
    std::size_t a = 0;
    while (a < axes_.size() && ++index[a] == admissible[a].size()) index[a++] = 0;
    if (a == axes_.size()) break;
  }
  std::sort(predicted.begin(), predicted.end(),
            [](const Predicted& x, const Predicted& y) { return x.cost < y.cost; });
  int tried = 0;
  for (const Predicted& p : predicted) {
    if (tried == options_.combinations) break;
    if (out_of_time()) {
      budget_spent_ = true;
      break;
    }
    if (!apply_setting(raw_, axes_, p.setting)) continue;
    Measured& m = measure("combination", p.setting);
    m.predicted_error = p.error;
    m.predicted_cost_ms = p.cost;
    ++tried;
  }
}

json Tuner::candidate_json(const Measured& m, double reference_error) const {
  json j = {{"stage", m.stage},
            {"setting", setting_json(m.setting)},
            {"changes", label_of(m.setting)},
            {"completed", m.run.completed},
            {"tets", m.run.tets}};
  if (m.stage == "given") {  // its settings need not be values of the axes
    j.erase("setting");
    j["changes"] = "the scene as given";
  }
  if (!m.run.completed) {
    j["failure"] = m.run.failure;
    return j;
  }
  j["error"] = m.error;
  j["error_with_reference"] = m.error + reference_error;
  if (std::isfinite(m.base_error) && m.stage == "screening") j["error_against_base"] = m.base_error;
  j["ms_per_step"] = m.run.ms_per_step;
  j["cost_ms"] = m.run.cost_ms;
  j["linear_iterations_per_step"] = m.run.linear_iterations_per_step;
  if (std::isfinite(m.predicted_error)) {
    j["predicted_error"] = m.predicted_error;
    j["predicted_cost_ms"] = m.predicted_cost_ms;
  }
  return j;
}

json Tuner::search_record(const ReferenceError& e_ref) const {
  json r;
  r["producer"] = "corofem tune";
  r["context"] = run_context();
  r["scene_file"] = name_;
  r["scene"] = raw_;
  r["target"] = options_.target;
  r["quantity"] = {{"kind", kTuneQuantities.name(quantity_.kind)}};
  if (quantity_.kind == TuneQuantity::Tip)
    r["quantity"]["point"] = {quantity_.tip.x(), quantity_.tip.y(), quantity_.tip.z()};
  if (quantity_.kind == TuneQuantity::Probe)
    r["quantity"]["box"] = {
        {quantity_.probe.lo.x(), quantity_.probe.lo.y(), quantity_.probe.lo.z()},
        {quantity_.probe.hi.x(), quantity_.probe.hi.y(), quantity_.probe.hi.z()}};
  r["error_definition"] =
      "relative error of the quantity against the reference's, plus the reference's own error "
      "(error_with_reference); the target applies to error_with_reference";
  r["cost_definition"] = scene_.analysis.type == AnalysisType::Dynamic
                             ? "median ms per step after 2 warm-up steps, divided by the time "
                               "factor (ms per step of the scene's own dt)"
                             : "ms of the whole static run, meshing and setup included";
  r["resolution"] = options_.axes.resolution_free ? "free" : "fixed";
  if (!resolution_note_.empty()) r["resolution_note"] = resolution_note_;
  r["budget_minutes"] = options_.budget_minutes;
  r["reference_error"] = e_ref.record;
  json axes = json::array();
  double grid = 1;
  for (const TuneAxis& axis : axes_) {
    json values = json::array();
    for (const AxisValue& v : axis.values) values.push_back(v.label);
    axes.push_back({{"name", axis.name},
                    {"values", values},
                    {"reference", axis.values[axis.reference].label}});
    grid *= static_cast<double>(axis.values.size());
  }
  r["axes"] = axes;
  int runs = 0;
  for (const Measured& m : measured_) runs += m.stage != "re-run";
  r["runs"] = runs;
  r["full_grid_runs"] = grid;
  r["search_fraction"] = runs / grid;
  r["skipped"] = skipped_;
  r["budget_spent"] = budget_spent_;
  return r;
}

json Tuner::candidates_record(double reference_error) const {
  // The Pareto front of everything measured (error with the reference's, cost).
  json candidates = json::array();
  std::vector<json*> on_front;
  std::vector<CostAndError> points;
  for (const Measured& m : measured_) candidates.push_back(candidate_json(m, reference_error));
  for (std::size_t i = 0; i < measured_.size(); ++i)
    if (measured_[i].run.completed && measured_[i].stage != "re-run") {
      on_front.push_back(&candidates[i]);
      points.push_back({measured_[i].run.cost_ms, measured_[i].error});
    }
  const std::vector<bool> front = pareto_front(points);
  for (std::size_t i = 0; i < on_front.size(); ++i) (*on_front[i])["pareto"] = bool(front[i]);
  return candidates;
}

TuneOutcome Tuner::answer(Measured choice, const ReferenceError& e_ref, const std::string& status,
                          const std::string& reason) {
  TuneOutcome out;
  json& r = out.record;
  r = search_record(e_ref);
  r["candidates"] = candidates_record(e_ref.value);
  std::optional<double> given_cost;  // read now: the re-run below grows measured_
  if (given_index_ >= 0) {
    const Measured& given = measured_[given_index_];
    r["given"] = candidate_json(given, e_ref.value);
    if (given.run.completed) given_cost = given.run.cost_ms;
  }
  out.tuned_scene = *apply_setting(raw_, axes_, choice.setting);
  json a = {{"status", status},
            {"reason", reason},
            {"setting", setting_json(choice.setting)},
            {"changes", label_of(choice.setting)},
            {"search", candidate_json(choice, e_ref.value)}};
  if (status == "met") {
    // The answer re-measured: the scene JSON written, read back as text, run on its own.
    const Measured& rerun = measure("re-run", choice.setting, json::parse(out.tuned_scene.dump()));
    a["rerun"] = candidate_json(rerun, e_ref.value);
    const bool met = rerun.run.completed && rerun.error + e_ref.value <= options_.target;
    if (rerun.run.completed) {
      a["margin"] = options_.target - (rerun.error + e_ref.value);
      if (given_cost) a["speedup_over_given"] = *given_cost / rerun.run.cost_ms;
    }
    if (status == "met" && !met) {
      a["status"] = "not met";
      a["reason"] = "the re-run missed the target: " +
                    (rerun.run.completed ? "error " + general_number(rerun.error + e_ref.value)
                                         : rerun.run.failure);
    }
  }
  out.exit_status = a["status"] == "met" ? 0 : 1;
  r["answer"] = a;
  r["elapsed_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return out;
}

TuneOutcome Tuner::run() {
  const Measured& reference = measure("reference", reference_setting_);
  if (!reference.run.completed)
    return answer(
        reference,
        {.value = 0,
         .record = {{"value", nullptr}, {"method", "not estimated: the reference did not run"}}},
        "not met", "solver-limited: the reference setting did not run: " + reference.run.failure);
  if (quantity_.kind == TuneQuantity::Tip)
    quantity_.tip = tip_point(reference.run.state, scene_.fixed);
  if (quantity_.kind == TuneQuantity::Probe &&
      vertices_in_box(reference.run.state.mesh.rest, quantity_.probe).empty())
    throw InputError(name_ + ": --probe: the box holds no vertex of the reference mesh");
  // The scene as the user wrote it, for the speed-up.
  std::vector<int> given_setting;
  for (const TuneAxis& axis : axes_) given_setting.push_back(axis.given);
  json as_given = raw_;
  as_given.erase("output");
  measure("given", given_setting, as_given);
  given_index_ = static_cast<int>(measured_.size()) - 1;
  // The resolutions first: the reference's own error decides what is left for the settings.
  const std::size_t resolution = 0;
  const int richardson_points = std::min<int>(3, static_cast<int>(axes_[resolution].values.size()));
  for (int i = 1; i < richardson_points; ++i) {
    std::vector<int> setting = reference_setting_;
    setting[resolution] = i;
    if (!screened(resolution, i)) measure("screening", setting);
  }
  const ReferenceError e_ref = reference_error();
  if (e_ref.value >= options_.target)
    return answer(measured_.front(), e_ref, "refused",
                  "discretization-limited: the reference's own error is estimated at " +
                      general_number(e_ref.value) + " (" +
                      e_ref.record["method"].get<std::string>() + "), not below the target " +
                      general_number(options_.target) +
                      "; refine the mesh, or tune against the scene's own mesh with --resolution "
                      "fixed");
  const double allowance = options_.target - e_ref.value;
  // The base: the scene's resolution with the reference's other settings (the reference itself
  // where the scene's resolution is the finest, or its run failed).
  base_setting_ = reference_setting_;
  base_setting_[resolution] = axes_[resolution].given;
  base_index_ = 0;
  for (std::size_t i = 0; i < measured_.size(); ++i)
    if (measured_[i].stage != "given" && measured_[i].setting == base_setting_ &&
        measured_[i].run.completed)
      base_index_ = static_cast<int>(i);
  if (base_index_ == 0) base_setting_ = reference_setting_;
  for (Measured& m : measured_)
    if (m.run.completed) m.base_error = against_base(m);
  for (std::size_t a = 0; a < axes_.size(); ++a) screen_axis(a, allowance);
  combine(allowance);
  const Measured* choice = &measured_.front();
  for (const Measured& m : measured_)
    if (m.stage != "given" && m.run.completed && m.error <= allowance &&
        m.run.cost_ms < choice->run.cost_ms)
      choice = &m;
  return answer(
      *choice, e_ref, "met",
      "the cheapest measured setting within the target" +
          std::string(budget_spent_ ? " (the budget ran out before the search ended)" : ""));
}

}  // namespace

TuneOutcome tune_scene(const json& raw, const std::filesystem::path& base_dir,
                       const std::string& name, const TuneOptions& options) {
  if (!(options.target > 0 && options.target < 1))
    throw InputError("tune: --target must be in (0, 1), got " + general_number(options.target));
  if (!(options.budget_minutes > 0)) throw InputError("tune: --budget must be positive minutes");
  return Tuner(raw, base_dir, name, options).run();
}

}  // namespace corofem
