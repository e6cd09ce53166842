#include "report/stability_study.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <sstream>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "mesh/tet_mesh.hpp"
#include "report/case_record.hpp"
#include "report/report_checkpoint.hpp"
#include "report/section_progress.hpp"
#include "report/stability_monitor.hpp"
#include "report/timed_run.hpp"
#include "report/units_side_by_side.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/time_step_scaling.hpp"

namespace corofem {
using nlohmann::json;

namespace {

/// The boundary surface: faces that belong to one tet only, each oriented with its normal
/// pointing away from that tet's fourth vertex (outward), as indices into `vertices`.
struct BoundarySurface {
  std::vector<int> vertices;                  ///< mesh vertices on the boundary, ascending
  std::vector<std::array<int, 3>> triangles;  ///< positions in `vertices`
};

BoundarySurface boundary_surface(const TetMesh& mesh) {
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>>
      faces;  // sorted -> count, oriented
  for (const Tet& t : mesh.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != skip) f[k++] = t[a];
      const Vec3 normal =
          (mesh.rest[f[1]] - mesh.rest[f[0]]).cross(mesh.rest[f[2]] - mesh.rest[f[0]]);
      if (normal.dot(mesh.rest[t[skip]] - mesh.rest[f[0]]) > 0) std::swap(f[1], f[2]);
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      auto& [count, oriented] = faces[key];
      ++count;
      oriented = f;
    }
  BoundarySurface surface;
  std::vector<int> position(mesh.rest.size(), -1);
  for (const auto& [key, face] : faces)
    if (face.first == 1)
      for (int v : key) position[v] = 0;
  for (std::size_t v = 0; v < position.size(); ++v)
    if (position[v] == 0) {
      position[v] = static_cast<int>(surface.vertices.size());
      surface.vertices.push_back(static_cast<int>(v));
    }
  for (const auto& [key, face] : faces)
    if (face.first == 1)
      surface.triangles.push_back(
          {position[face.second[0]], position[face.second[1]], position[face.second[2]]});
  return surface;
}

double round4(double x) {
  return std::isfinite(x) ? std::round(x * 1e4) / 1e4 : 0.0;
}

/// The record's measurements of a run that completed or diverged: its status, flutter, energy,
/// inversions and series.
void add_measurements(const StabilityMonitor& monitor, const TimedRun& run, bool diverged,
                      const json& result, json& record) {
  record["completed"] = true;
  const std::vector<int>& inverted = monitor.inverted_series();
  const int inverted_final = inverted.empty() ? 0 : inverted.back();
  record["status"] = diverged                  ? "diverged"
                     : monitor.flutters()      ? "flutter"
                     : monitor.stuck(run.tets) ? "stuck"
                                               : "stable";
  record["diverged_step"] = diverged ? json(monitor.last_step() + 1) : json(nullptr);
  if (diverged) record["divergence"] = result["error"];
  const bool flutter_measured = monitor.flutter_rms_rad() >= 0 && !diverged;
  record["flutter_rms_rad"] = flutter_measured ? json(monitor.flutter_rms_rad()) : json(nullptr);
  record["flutter_max_rad"] = flutter_measured ? json(monitor.flutter_max_rad()) : json(nullptr);
  record["inverted_max"] =
      inverted.empty() ? 0 : *std::max_element(inverted.begin(), inverted.end());
  record["inverted_final"] = inverted_final;
  const std::vector<double>& kinetic = monitor.kinetic_series();
  record["kinetic_energy_final"] = kinetic.empty() ? json(nullptr) : finite_or_null(kinetic.back());
  record["residual_final"] = diverged ? json(nullptr) : finite_or_null(run.result.residual);
  record["steps_run"] = monitor.last_step();
  record["asymmetry"] =
      monitor.asymmetry_median() >= 0 ? json(monitor.asymmetry_median()) : json(nullptr);
  record["energy_error"] = !diverged && monitor.energy_error() >= 0
                               ? finite_or_null(monitor.energy_error())
                               : json(nullptr);
  record["cause"] = nullptr;
  record["tets"] = run.tets;
  if (record["integrator"] == "newton" && !diverged)  // how hard the robust Newton worked
    record["newton"] = {{"step_cuts", run.result.step_cuts},
                        {"step_halvings", run.result.newton_halvings},
                        {"steps_at_floor", run.result.newton_at_floor},
                        {"potential_fallbacks", run.result.potential_fallbacks}};
  record["series"] = {{"rotation_change_rms_rad", monitor.rms_series()},
                      {"rotation_change_max_rad", monitor.max_series()},
                      {"kinetic_energy", kinetic},
                      {"inverted", inverted}};
}

/// The final pose of a run's boundary surface, with each vertex's largest rotation change in the
/// settled window, for the pose chart.
json pose_record(const StabilityMonitor& monitor, const TimedRun& run, const std::string& scene_id,
                 const StabilityRun& spec, const json& status) {
  const BoundarySurface surface = boundary_surface(run.mesh);
  json rest = json::array(), points = json::array(), values = json::array(),
       triangles = json::array();
  for (int v : surface.vertices) {
    const Vec3& x0 = run.mesh.rest[v];
    const Vec3 x = x0 + run.result.displacement.segment<3>(3 * v);
    rest.push_back({round4(x0.x()), round4(x0.y()), round4(x0.z())});
    points.push_back({round4(x.x()), round4(x.y()), round4(x.z())});
    values.push_back(round4(monitor.vertex_change()[v]));
  }
  for (const auto& t : surface.triangles) triangles.push_back(t);
  return {{"scene", scene_id},
          {"method", spec.method.name()},
          {"integrator", kIntegrators.name(spec.integrator)},
          {"status", status},
          {"rest_points", rest},
          {"triangles", triangles},
          {"points", points},
          {"rotation_change_max_rad", values}};
}

}  // namespace

double FlutterThresholds::blowup_displacement(const std::vector<Vec3>& rest) const {
  const auto [lo, hi] = bounding_box(rest);
  return blowup_factor * (hi - lo).norm();
}

json run_stability_case(const json& scene, const std::string& scene_id, const StabilityRun& spec,
                        int ramp_steps, int hold_steps, json* pose,
                        const std::filesystem::path& vtu_dir) {
  const std::string method = spec.method.name();
  const std::string integrator = kIntegrators.name(spec.integrator);
  json s = *time_step_scaled(scene, 1, spec.refinement);  // always whole
  s["analysis"]["rotation"] = method;
  s["analysis"]["integrator"] = integrator;
  ramp_steps *= spec.refinement;
  hold_steps *= spec.refinement;
  const double dt = s["analysis"]["dt"].get<double>();
  const json rayleigh = s["analysis"].value("rayleigh", json::object());
  StabilityMonitor monitor(spec.method, ramp_steps, hold_steps, dt, rayleigh.value("alpha", 0.0),
                           rayleigh.value("beta", 0.0), vtu_dir);
  json record = {{"scene", scene_id}, {"method", method},         {"integrator", integrator},
                 {"dt", dt},          {"ramp_steps", ramp_steps}, {"hold_steps", hold_steps}};
  TimedRun run;
  TimedRunOptions options;
  options.on_step = [&](const StepState& st, const FeProblem& problem) {
    monitor.observe(st, problem);
  };
  json result = record_case(record, [&] {
    run = timed_run(s, scene_id, options);
    return json::object();
  });
  // A numerical fault (NaN, a lost factorization, a blow-up) is the measurement "diverged"; bad
  // input or an internal error means the case did not run.
  const bool diverged =
      !result["completed"].get<bool>() &&
      (result["error"]["kind"] == "numerical" || result["error"]["kind"] == "not_converged");
  if (!result["completed"].get<bool>() && !diverged) {
    record["completed"] = false;
    record["error"] = result["error"];
    record["status"] = "failed";
    return record;
  }
  add_measurements(monitor, run, diverged, result, record);
  if (pose && !diverged) *pose = pose_record(monitor, run, scene_id, spec, record["status"]);
  return record;
}

namespace {

/// A run's RMS rotation change over the settled window per second (negative: not measured): the
/// rate of motion, comparable between step sizes where the change per step is not.
double rotation_rate(const json& run) {
  // contains() first: operator[] on a const json with the key missing is undefined.
  return run.contains("flutter_rms_rad") && run["flutter_rms_rad"].is_number()
             ? run["flutter_rms_rad"].get<double>() / run["dt"].get<double>()
             : -1;
}

/// Motion the refined reference shows at at least this share of a fluttering run's rate is the
/// scene's (it converges under refinement to itself, not to rest); below it, the flutter is
/// numerical.
constexpr double kSameMotionShare = 0.5;

}  // namespace

void attribute_causes(std::vector<json*>& group, const json* reference) {
  const auto describe = [](const json& run) {
    std::ostringstream text;
    text << run["integrator"].get<std::string>() << " at dt " << run["dt"].get<double>() << ": "
         << run["status"].get<std::string>();
    if (run["flutter_max_rad"].is_number())
      text << " (flutter max " << run["flutter_max_rad"].get<double>() << " rad, RMS "
           << rotation_rate(run) << " rad/s)";
    if (run["diverged_step"].is_number())
      text << " (at step " << run["diverged_step"].get<int>() << ")";
    if (run["status"] == "stuck")
      text << " (" << run["inverted_final"].get<int>() << " elements inverted at the end)";
    return text.str();
  };
  const bool refined = reference && (*reference)["status"] != "failed";
  for (json* r : group) {
    if ((*r)["status"] == "stable" || (*r)["status"] == "failed") continue;
    // The comparisons: the other runs at the same step (the other integrator) or a smaller one.
    const json* witness = nullptr;  // one of them stable: the failure is not the method's
    std::vector<const json*> others;
    for (const json* o : group)
      if (o != r && (*o)["status"] != "failed" &&
          (*o)["dt"].get<double>() <= (*r)["dt"].get<double>()) {
        others.push_back(o);
        if ((*o)["status"] == "stable" && !witness) witness = o;
      }
    if (witness) {
      (*r)["cause"] = "integrator";
      (*r)["cause_detail"] = describe(*r) + "; but " + describe(*witness);
      continue;
    }
    if (refined) {
      // The same method under Newton at a step a fraction of the smallest: what the scene does
      // when the time integration no longer matters.
      const json& ref = *reference;
      const std::string against = "; refined reference " + describe(ref);
      const std::string status = (*r)["status"];
      // A method that blows up or leaves the body inverted at the small step too fails by itself;
      // a Newton that cannot solve the small steps (even cut to 1/16) is the integrator's failure
      // (the method's own would show as energy created or a blow-up).
      const bool newton_unsolved = ref["status"] == "diverged" && ref.contains("divergence") &&
                                   ref["divergence"].value("kind", "") == "not_converged";
      const bool fails_refined =
          (ref["status"] == "diverged" && !newton_unsolved) || ref["status"] == "stuck";
      std::string cause = fails_refined ? "method" : "integrator";
      if (status == "flutter" && !fails_refined && !newton_unsolved &&
          rotation_rate(ref) >= kSameMotionShare * rotation_rate(*r))
        cause = "scene";  // the motion is there at the small step too: physical, not numerical
      (*r)["cause"] = cause;
      (*r)["cause_detail"] = describe(*r) + against;
      continue;
    }
    const bool newton_only_unconverged =
        !others.empty() && std::all_of(others.begin(), others.end(), [](const json* o) {
          return o->contains("divergence") && (*o)["divergence"]["kind"] == "not_converged";
        });
    if (others.empty() || newton_only_unconverged) {
      (*r)["cause"] = nullptr;
      (*r)["cause_detail"] =
          describe(*r) + (others.empty()
                              ? "; no run under the other integrator or at a smaller step"
                              : "; Newton did not converge in the runs to compare");
    } else {
      std::string also;
      for (const json* o : others) also += "; also " + describe(*o);
      (*r)["cause"] = "method";
      (*r)["cause_detail"] = describe(*r) + also;
    }
  }
}

bool needs_refined_reference(const std::vector<json>& group) {
  for (const json& r : group) {
    if (r["status"] == "stable" || r["status"] == "failed") continue;
    const bool explained = std::any_of(group.begin(), group.end(), [&](const json& o) {
      return o["status"] == "stable" && o["dt"].get<double>() <= r["dt"].get<double>();
    });
    if (!explained) return true;
  }
  return false;
}

void attribute_scene_causes(json& runs, const std::string& scene) {
  // No run of the scene stable: no method under either integrator at any step settles it.
  const bool settled = std::any_of(runs.begin(), runs.end(), [&](const json& r) {
    return r["scene"] == scene && r["status"] == "stable";
  });
  for (json& r : runs) {
    if (r["scene"] != scene || r["status"] == "stable" || r["status"] == "failed") continue;
    if (r["cause"] == "scene") {
      r["status"] = "motion";
      for (const json& o : runs)
        if (o["scene"] == scene && o["method"] != r["method"] && o["status"] == "stable" &&
            o["integrator"] == r["integrator"] && o["dt"] == r["dt"]) {
          r["status"] = "flutter";
          r["cause"] = "method";
          r["cause_detail"] = r["cause_detail"].get<std::string>() + "; but " +
                              o["method"].get<std::string>() + " settles the scene there";
          break;
        }
    } else if (!settled) {
      // A method fails by itself only where it is confirmed: a blow-up or a body left inverted
      // (energy created shows as one of them or as flutter that another method settles).
      const bool confirmed =
          r["status"] == "stuck" || (r["status"] == "diverged" && r.contains("divergence") &&
                                     r["divergence"].value("kind", "") == "numerical");
      if (confirmed) continue;
      r["cause"] = "scene";
      r["cause_detail"] = r["cause_detail"].get<std::string>() +
                          "; no method under either integrator at any step settles " + scene +
                          ": beyond every method";
    }
  }
}

namespace {

json stability_verdicts(const json& runs) {
  // Per method: the paper's claim (stable everywhere) held or not, and why not. Failures of the
  // scene (motion the refined reference shows too, no method settling it) are not the method's.
  std::map<std::string, json> by_method;
  for (const json& r : runs) {
    json& v = by_method[r["method"].get<std::string>()];
    if (v.is_null())
      v = {{"runs", 0},          {"not_stable", json::array()},
           {"method_caused", 0}, {"integrator_caused", 0},
           {"scene_caused", 0},  {"scenes_beyond_every_method", json::array()}};
    v["runs"] = v["runs"].get<int>() + 1;
    if (r["status"] == "stable") continue;
    v["not_stable"].push_back({{"scene", r["scene"]},
                               {"integrator", r["integrator"]},
                               {"dt", r["dt"]},
                               {"status", r["status"]},
                               {"cause", r["cause"]}});
    for (const char* cause : {"method", "integrator", "scene"})
      if (r["cause"] == cause) {
        const std::string key = std::string(cause) + "_caused";
        v[key] = v[key].get<int>() + 1;
      }
    json& beyond = v["scenes_beyond_every_method"];
    if (r["cause"] == "scene" &&
        std::find(beyond.begin(), beyond.end(), r["scene"]) == beyond.end())
      beyond.push_back(r["scene"]);
  }
  json out = json::object();
  for (auto& [method, v] : by_method) {
    const int by_method_count = v["method_caused"], by_integrator = v["integrator_caused"],
              by_scene = v["scene_caused"];
    const int unattributed =
        static_cast<int>(v["not_stable"].size()) - by_method_count - by_integrator - by_scene;
    std::string verdict =
        v["not_stable"].empty() ? "stable in every run"
        : by_method_count > 0
            ? "fails by itself in some scene (under both integrators, at both steps and at the "
              "refined step)"
        : by_integrator > 0 ? "stable once the integrator is: every failure goes with the "
                              "linearly implicit step or the larger dt"
        : by_scene > 0      ? "stable wherever some method settles the scene"
                            : "failures without an attributable cause";
    if (by_scene > 0) {
      std::string scenes;
      for (const json& scene : v["scenes_beyond_every_method"])
        scenes += (scenes.empty() ? "" : ", ") + scene.get<std::string>();
      verdict += "; beyond every method: " + scenes;
    }
    if (unattributed > 0 && by_method_count + by_integrator + by_scene > 0)
      verdict += "; " + std::to_string(unattributed) + " failures without an attributable cause";
    v["verdict"] = verdict;
    out[method] = v;
  }
  return out;
}

}  // namespace

MethodRuns run_method_on_scene(const json& scene, const std::string& id, RotationMethod method,
                               const MethodPlan& plan) {
  MethodRuns out;
  const auto run = [&](const StabilityRun& spec, bool keep_pose) {
    const std::string integrator = kIntegrators.name(spec.integrator);
    if (plan.progress)
      *plan.progress << plan.progress_prefix << ", " << integrator << ", dt 0.01/"
                     << spec.refinement << std::endl;
    json pose;
    const auto vtu_dir = plan.vtu_dir.empty() || !keep_pose
                             ? std::filesystem::path()
                             : plan.vtu_dir / (method.name() + "-" + integrator);
    json record = run_stability_case(scene, id, spec, plan.ramp_steps, plan.hold_steps,
                                     keep_pose ? &pose : nullptr, vtu_dir);
    if (!pose.is_null()) out.poses.push_back(std::move(pose));
    return record;
  };
  for (const Integrator integrator : {Integrator::LinearImplicit, Integrator::Newton})
    out.runs.push_back(run({method, integrator, 1}, true));
  // The smaller step decides the cause of a run that is not stable; where both integrators are
  // stable at dt there is nothing to attribute.
  const bool all_stable = std::all_of(out.runs.begin(), out.runs.end(),
                                      [](const json& r) { return r["status"] == "stable"; });
  if (plan.smaller_step_always || (plan.smaller_step && !all_stable))
    for (const Integrator integrator : {Integrator::LinearImplicit, Integrator::Newton})
      out.runs.push_back(run({method, integrator, 2}, false));
  // A failure nothing in the group explains is checked against the scene refined in time.
  if (plan.refined_reference && needs_refined_reference(out.runs)) {
    out.reference = run({method, Integrator::Newton, kReferenceRefinement}, false);
    out.reference.erase("series");
  }
  std::vector<json*> members;
  for (json& r : out.runs) members.push_back(&r);
  attribute_causes(members, out.reference.is_null() ? nullptr : &out.reference);
  return out;
}

namespace {

/// Every (scene, method) group of the study: groups[k] holds scene k's, in the extractors' order.
/// The groups run side by side (report/units_side_by_side.hpp); with --vtu one at a time (the
/// frame writers share the partial-file registry).
std::vector<std::vector<MethodRuns>> run_groups(const ReportConfig& config,
                                                const std::vector<std::string>& scenes,
                                                const std::vector<json>& scene_specs) {
  struct Group {
    std::size_t scene, slot;
    RotationMethod method;
  };
  std::vector<Group> plan_of;
  std::vector<std::vector<MethodRuns>> groups(scenes.size());
  for (std::size_t k = 0; k < scenes.size(); ++k)
    for (RotationMethod method : rotation_methods())
      if (method.traits().compared) {
        plan_of.push_back({k, groups[k].size(), method});
        groups[k].emplace_back();
      }
  const int total = static_cast<int>(plan_of.size());
  SectionProgress progress(config.progress, "stability", total);
  run_units_side_by_side(
      total, config.vtu ? 1 : thread_count(), config.progress, [&](int g, std::ostream* lines) {
        const auto& [k, slot, method] = plan_of[static_cast<std::size_t>(g)];
        const std::string& id = scenes[k];
        MethodPlan plan{config.stability_ramp(), config.stability_hold()};
        plan.smaller_step_always = config.mode == ReportConfig::Mode::Full;
        plan.smaller_step = config.mode != ReportConfig::Mode::Smoke;
        plan.refined_reference = config.mode != ReportConfig::Mode::Smoke;
        plan.progress_prefix = progress.begin(id + ": " + method.name());
        plan.progress = lines;
        if (config.vtu) plan.vtu_dir = config.out_dir / "vtu" / id;
        // A unit, kept for --resume (a kept unit writes no VTU frames again).
        const json unit = report_unit(
            config, "stability", id + ": " + method.name(),
            [&] {
              const MethodRuns m = run_method_on_scene(scene_specs[k], id, method, plan);
              return json{{"runs", m.runs}, {"reference", m.reference}, {"poses", m.poses}};
            },
            plan.progress_prefix);
        groups[k][slot] = {unit["runs"].get<std::vector<json>>(), unit["reference"],
                           unit["poses"].get<std::vector<json>>()};
        progress.finish();
      });
  return groups;
}

}  // namespace

json run_stability_study(const ReportConfig& config) {
  const FlutterThresholds thresholds;
  json out = {
      {"thresholds",
       {{"flutter_max_rad", thresholds.max_rad},
        {"flutter_rms_rad", thresholds.rms_rad},
        {"blowup_factor", thresholds.blowup_factor},
        {"stuck_inverted_share", thresholds.stuck_inverted_share},
        {"window", "second half of the hold (loads constant)"},
        {"statuses",
         "diverged: NaN/inf, a lost factorization, |u| > blowup_factor x diagonal, or Newton "
         "not converging even with the step cut to dt/16; "
         "flutter: max or RMS rotation change per step above its threshold; stuck: more than "
         "stuck_inverted_share of the elements inverted at the end of the hold (a body that did "
         "not recover); motion: flutter that the same method under Newton at dt/4 shows too (at "
         "least half the rate in rad/s) and no method settles, the scene's physical motion "
         "(cause scene); stable otherwise"}}},
      {"newton",
       "fully implicit Euler by Newton with a line search on the incremental potential where "
       "the force has one (polar, polar-fixed), safeguarded full steps otherwise; a step that "
       "does not converge is retried as two of dt/2, at most 4 times deep (newton.step_cuts); a "
       "step converges at 1e-8 of its terms, or within 100x that where an iteration no longer "
       "halves the residual (rounding floor: newton.steps_at_floor)"},
      {"ramp_steps", config.stability_ramp()},
      {"hold_steps", config.stability_hold()},
      {"size", size_name(config.stability_size())},
      {"runs", json::array()},
      {"references", json::array()},
      {"poses", json::array()}};
  out["scenes"] = json::object();
  out["surfaces"] = json::object();
  const std::vector<std::string> scenes = config.stability_scenes();
  std::vector<json> scene_specs;
  for (const std::string& id : scenes) {
    json scene = stability_scene(id, config.stability_size(), config.stability_ramp(),
                                 config.stability_hold(), config.models_dir);
    // The smoke report (seconds, for the report's own tests, also under the sanitizers) caps
    // Newton at 8 iterations and one cut a step: its scenes are brutal (75 degrees of twist a
    // step), and steps cut four times at 30 iterations each took its study from 8 to 22 s.
    if (config.mode == ReportConfig::Mode::Smoke) {
      scene["analysis"]["max_iterations"] = 8;
      scene["analysis"]["max_step_cuts"] = 1;
    }
    out["scenes"][id] = scene;
    scene_specs.push_back(std::move(scene));
  }
  std::vector<std::vector<MethodRuns>> groups = run_groups(config, scenes, scene_specs);
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const std::string& id = scenes[k];
    const json& scene = scene_specs[k];
    for (MethodRuns& m : groups[k]) {
      for (json& pose : m.poses) {
        // The rest surface is the scene's, the same for every run: stored once.
        if (!out["surfaces"].contains(id))
          out["surfaces"][id] = {{"rest_points", pose["rest_points"]},
                                 {"triangles", pose["triangles"]}};
        pose.erase("rest_points");
        pose.erase("triangles");
        out["poses"].push_back(std::move(pose));
      }
      for (json& r : m.runs) out["runs"].push_back(std::move(r));
      if (!m.reference.is_null()) out["references"].push_back(std::move(m.reference));
    }
    attribute_scene_causes(out["runs"], id);
    for (json& pose : out["poses"])  // a pose shows its run's final status
      for (const json& r : out["runs"])
        if (pose["scene"] == id && r["scene"] == id && r["method"] == pose["method"] &&
            r["integrator"] == pose["integrator"] && r["dt"] == scene["analysis"]["dt"])
          pose["status"] = r["status"];
  }
  out["verdicts"] = stability_verdicts(out["runs"]);
  return out;
}

json take_stability_frames(json& study) {
  json frames = {{"series", json::array()},
                 {"poses", study.value("poses", json::array())},
                 {"surfaces", study.value("surfaces", json::object())}};
  study.erase("poses");
  study.erase("surfaces");
  for (json& run : study["runs"]) {
    frames["series"].push_back(run.contains("series") ? std::move(run["series"]) : json(nullptr));
    run.erase("series");
  }
  return frames;
}

ReportSectionTraits stability_section() {
  return {"stability", "stability", "stability.json",
          "every rotation extractor on scenes built to break them, under linearly\n"
          "implicit and Newton Euler at two steps: stable, flutter or diverged, with\n"
          "flutter, inversion, energy and asymmetry measurements and the cause of each\n"
          "failure (method or integrator)",
          [](const ReportConfig& config, std::vector<ReportRecord>& beside) {
            json study = run_stability_study(config);
            beside.push_back(
                {"stability_frames.json", "stability frames", take_stability_frames(study)});
            return study;
          }};
}

}  // namespace corofem
