#include "report/speed_accuracy.hpp"

#include <limits>
#include <ostream>

#include "core/statistics.hpp"
#include "report/analysis_variant.hpp"
#include "report/case_record.hpp"
#include "report/report_checkpoint.hpp"
#include "report/section_progress.hpp"
#include "report/timed_run.hpp"
#include "rotation/rotation_extractor.hpp"
#include "solver/petsc_solver.hpp"

namespace corofem {
using nlohmann::json;

namespace {

double relative_error(const Eigen::VectorXd& u, const Eigen::VectorXd& reference) {
  const double norm = reference.norm();
  return norm > 0 ? (u - reference).norm() / norm : (u - reference).norm();
}

/// Settings of the solver sweep (all with energy-newton rotations; multigrid on the scene's
/// re-meshed hierarchy unless the setting says "hierarchy": "lattice").
std::vector<AnalysisVariant> solver_settings(const ReportConfig& config, int levels) {
  constexpr HierarchyKind lattice = HierarchyKind::Lattice;
  std::vector<AnalysisVariant> settings;
  for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8})
    settings.push_back({.solver = SolverKind::Mgpcg, .tolerance = tolerance});
  for (int vcycles : {1, 2, 4})
    settings.push_back({.solver = SolverKind::Multigrid, .vcycles = vcycles});
  for (int smoothing : {2, 3})
    settings.push_back({.solver = SolverKind::Multigrid, .vcycles = 1, .smoothing = smoothing});
  for (int l = 2; l <= levels + 1; ++l)
    if (l != levels)
      settings.push_back({.solver = SolverKind::Mgpcg, .tolerance = 1e-4, .levels = l});
  // The same solvers on the covering lattice hierarchy (the others run on re-meshed levels).
  for (double tolerance : {1e-2, 1e-4, 1e-6})
    settings.push_back({.solver = SolverKind::Mgpcg, .hierarchy = lattice, .tolerance = tolerance});
  for (int vcycles : {1, 2})
    settings.push_back({.solver = SolverKind::Multigrid, .hierarchy = lattice, .vcycles = vcycles});
  settings.push_back({.solver = SolverKind::JacobiPcg, .tolerance = 1e-4});
  // The coarse operators kept while the fine stiffness moved little (MG-PCG at the table's 1e-4).
  for (double refresh : {0.05, 0.1})
    settings.push_back(
        {.solver = SolverKind::Mgpcg, .tolerance = 1e-4, .galerkin_refresh = refresh});
  if (have_petsc())  // the algebraic multigrid users would pick instead
    for (const SolverKind rival :
         {SolverKind::PetscGamg, SolverKind::HypreBoomeramg, SolverKind::PetscMg})
      for (double tolerance : {1e-4, 1e-6})
        settings.push_back({.solver = rival, .tolerance = tolerance});
  if (config.mode == ReportConfig::Mode::Smoke) settings.resize(3);
  return settings;
}

/// Cheapest completed point with error <= tolerance (excluding the reference itself).
json cheapest_meeting(const json& points, double tolerance) {
  json best = nullptr;
  for (const json& p : points) {
    if (!p.value("completed", false) || p.value("is_reference", false)) continue;
    if (!p["rel_error"].is_number() || p["rel_error"].get<double>() > tolerance) continue;
    if (best.is_null() ||
        p["time_per_step_ms"].get<double>() < best["time_per_step_ms"].get<double>())
      best = p;
  }
  return best.is_null() ? json(nullptr)
                        : json{{"label", best["label"]},
                               {"time_per_step_ms", best["time_per_step_ms"]},
                               {"rel_error", best["rel_error"]}};
}

}  // namespace

void mark_pareto_front(json& points, const std::string& sweep) {
  auto candidate = [&](const json& p) {
    return p.value("completed", false) && p.contains("rel_error") && p["rel_error"].is_number() &&
           !p.value("is_reference", false) && (sweep.empty() || p.value("sweep", "") == sweep);
  };
  std::vector<json*> candidates;
  std::vector<CostAndError> values;
  for (json& p : points) {
    if (candidate(p)) {
      candidates.push_back(&p);
      values.push_back({p["time_per_step_ms"], p["rel_error"]});
    } else if (p.value("completed", false) && (sweep.empty() || p.value("sweep", "") == sweep)) {
      p["pareto"] = false;  // a completed reference: what the errors are measured against
    }
  }
  const std::vector<bool> front = pareto_front(values);
  for (std::size_t i = 0; i < candidates.size(); ++i) (*candidates[i])["pareto"] = bool(front[i]);
}

namespace {

/// One scene's sweeps: each setting's time per step against its error, the points in `entry`.
struct SceneSweeps {
  const ReportConfig& config;
  std::string model, id;
  json scene;
  int steps = 0, warmup = 0;
  json entry;
  std::string progress_prefix;  ///< "report: speed-accuracy 2/3: cantilever-small (...)"

  void say(const std::string& what) const {
    if (config.progress) *config.progress << progress_prefix << ": " << what << std::endl;
  }

  /// Runs the scene's `variant` and adds its point, its error given by `error`.
  void point(const std::string& sweep, const AnalysisVariant& variant,
             const std::function<double(const TimedRun&)>& error, bool is_reference = false) {
    const std::string label = label_of(variant);
    say(sweep + ": " + label);
    entry["points"].push_back(
        record_case({{"sweep", sweep}, {"setting", to_json(variant)}, {"label", label}}, [&] {
          const TimedRun run = timed_run(with_analysis(scene, variant), id, {});
          return json{{"time_per_step_ms", run.median_ms("step", warmup)},
                      {"step_samples_ms", run.samples_ms(warmup).value("step", json::array())},
                      {"rel_error", finite_or_null(error(run))},
                      {"tets", run.tets},
                      {"iterations_per_step", run.median_iterations(warmup)},
                      {"is_reference", is_reference}};
        }));
  }

  /// Resolution: the probe's displacement at each size, against the finest completed one.
  void resolution_sweep() {
    const json probe = probe_box(model);
    json points = json::array();
    for (SceneSize s : config.resolution_sizes()) {
      const json setting = {{"resolution", size_name(s)}};
      say("resolution: " + size_name(s));
      points.push_back(record_case(
          {{"sweep", "resolution"}, {"setting", setting}, {"label", size_name(s)}}, [&] {
            const TimedRun run = timed_run(
                table_scene(model, s, steps, config.default_tolerance(), config.models_dir),
                model + "-" + size_name(s), {});
            const Vec3 value = run.probe(probe);
            return json{{"time_per_step_ms", run.median_ms("step", warmup)},
                        {"tets", run.tets},
                        {"probe_displacement", {value.x(), value.y(), value.z()}}};
          }));
    }
    json* finest = nullptr;
    for (json& p : points)
      if (p["completed"]) finest = &p;
    for (json& p : points) {
      if (!p["completed"] || !finest) continue;
      const auto& a = p["probe_displacement"];
      const auto& b = (*finest)["probe_displacement"];
      const Vec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]);
      p["rel_error"] =
          finite_or_null(pb.norm() > 0 ? (pa - pb).norm() / pb.norm() : (pa - pb).norm());
      p["is_reference"] = &p == finest;
      entry["points"].push_back(p);
    }
  }

  /// Each sweep's Pareto front and the cheapest point meeting its target.
  void mark_fronts(const AccuracyTargets& targets) {
    for (const char* sweep : {"solver", "rotation", "resolution"})
      mark_pareto_front(entry["points"], sweep);
    auto subset_of = [&](const char* sweep) {
      json subset = json::array();
      for (const json& p : entry["points"])
        if (p["sweep"] == sweep) subset.push_back(p);
      return subset;
    };
    entry["cheapest_meeting_target"] = {
        {"solver", cheapest_meeting(subset_of("solver"), targets.solver)},
        {"rotation", cheapest_meeting(subset_of("rotation"), targets.rotation)},
        {"resolution", cheapest_meeting(subset_of("resolution"), targets.resolution)}};
  }
};

/// The solver, rotation and resolution sweeps of one model at its sweep size.
json scene_sweeps(const ReportConfig& config, const std::string& model,
                  const AccuracyTargets& targets, const std::string& progress_prefix) {
  const int steps = config.sweep_steps();
  const SceneSize size = config.sweep_size(model);
  SceneSweeps s{config,
                model,
                model + "-" + size_name(size),
                table_scene(model, size, steps, config.default_tolerance(), config.models_dir),
                steps,
                std::min(2, steps - 1),
                json(),
                ""};
  s.progress_prefix = progress_prefix;
  s.entry = {{"scene", s.id}, {"model", model}, {"steps", steps}, {"points", json::array()}};
  // References at this resolution.
  Eigen::VectorXd u_ref, u_exact;
  s.say("references (CHOLMOD)");
  const json refs = record_case({}, [&] {
    const AnalysisVariant cholmod{.solver = SolverKind::Cholmod};
    u_ref = timed_run(with_analysis(s.scene, cholmod), s.id, {}).result.displacement;
    AnalysisVariant exact = cholmod;
    exact.rotation = RotationMethod::EnergyExact;
    u_exact = timed_run(with_analysis(s.scene, exact), s.id, {}).result.displacement;
    return json::object();
  });
  if (!refs["completed"]) {
    s.entry["completed"] = false;
    s.entry["error"] = refs["error"];
    return s.entry;
  }
  const auto against = [](const Eigen::VectorXd& reference) {
    return [ref = &reference](const TimedRun& run) {
      return relative_error(run.result.displacement, *ref);
    };
  };
  const int levels = s.scene["analysis"]["levels"];
  for (const AnalysisVariant& setting : solver_settings(config, levels))
    s.point("solver", setting, against(u_ref));
  s.point("solver", {.solver = SolverKind::Cholmod}, against(u_ref), true);
  for (RotationMethod method : rotation_methods()) {
    if (!method.traits().compared) continue;
    if (config.mode == ReportConfig::Mode::Smoke && !method.traits().in_smoke) continue;
    s.point("rotation", {.rotation = method}, against(u_exact));
  }
  s.resolution_sweep();
  s.mark_fronts(targets);
  s.entry["completed"] = true;
  return s.entry;
}

}  // namespace

json run_speed_accuracy(const ReportConfig& config) {
  const AccuracyTargets targets;
  json out = {
      {"targets",
       {{"solver", targets.solver},
        {"rotation", targets.rotation},
        {"resolution", targets.resolution}}},
      {"error_definitions",
       {{"solver",
         "|u - u_ref| / |u_ref| of the last step's displacement, u_ref: CHOLMOD with the same "
         "rotations and mesh"},
        {"rotation",
         "|u - u_ref| / |u_ref|, u_ref: energy-exact rotations with CHOLMOD (the exact minimizer)"},
        {"resolution",
         "|p - p_ref| / |p_ref| of the mean displacement of a probe region, p_ref: the finest "
         "resolution"}}},
      {"scenes", json::array()}};
  const std::vector<std::string> models = config.models();
  SectionProgress progress(config.progress, "speed-accuracy", static_cast<int>(models.size()));
  for (const std::string& model : models) {  // a unit each, kept for --resume
    const std::string prefix = progress.begin(model + "-" + size_name(config.sweep_size(model)));
    out["scenes"].push_back(report_unit(
        config, "speed-accuracy", model,
        [&] { return scene_sweeps(config, model, targets, prefix); }, prefix));
    progress.finish();
  }
  return out;
}

ReportSectionTraits speed_accuracy_section() {
  return {"speed-accuracy", "speed-accuracy", "speed_accuracy.json",
          "time per step against error for solver settings, rotation methods and\n"
          "resolutions, with the Pareto front and the cheapest setting meeting targets",
          [](const ReportConfig& config, std::vector<ReportRecord>&) {
            return run_speed_accuracy(config);
          }};
}

}  // namespace corofem
