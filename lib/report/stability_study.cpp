#include "report/stability_study.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <sstream>

#include "core/errors.hpp"
#include "report/case_record.hpp"
#include "report/stability_monitor.hpp"
#include "report/timed_run.hpp"
#include "rotation/rotation_extractor.hpp"

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
          {"method", kRotationMethods.name(spec.method)},
          {"integrator", kIntegrators.name(spec.integrator)},
          {"status", status},
          {"rest_points", rest},
          {"triangles", triangles},
          {"points", points},
          {"rotation_change_max_rad", values}};
}

}  // namespace

json refined_scene(const json& scene, int k) {
  json s = scene;
  s["analysis"]["dt"] = s["analysis"]["dt"].get<double>() / k;
  s["analysis"]["steps"] = s["analysis"]["steps"].get<int>() * k;
  for (const char* loads : {"forces", "moves"})
    if (s.contains(loads))
      for (json& load : s[loads])
        for (const char* key : {"ramp_steps", "release_step"})
          if (load.contains(key)) load[key] = load[key].get<int>() * k;
  return s;
}

json run_stability_case(const json& scene, const std::string& scene_id, const StabilityRun& spec,
                        int ramp_steps, int hold_steps, json* pose,
                        const std::filesystem::path& vtu_dir) {
  const std::string method = kRotationMethods.name(spec.method);
  const std::string integrator = kIntegrators.name(spec.integrator);
  json s = refined_scene(scene, spec.refinement);
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

void attribute_causes(std::vector<json*>& group) {
  const auto describe = [](const json& run) {
    std::ostringstream text;
    text << run["integrator"].get<std::string>() << " at dt " << run["dt"].get<double>() << ": "
         << run["status"].get<std::string>();
    if (run["flutter_max_rad"].is_number())
      text << " (flutter max " << run["flutter_max_rad"].get<double>() << " rad)";
    if (run["diverged_step"].is_number())
      text << " (at step " << run["diverged_step"].get<int>() << ")";
    if (run["status"] == "stuck")
      text << " (" << run["inverted_final"].get<int>() << " elements inverted at the end)";
    return text.str();
  };
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
    const bool newton_only_unconverged =
        !others.empty() && std::all_of(others.begin(), others.end(), [](const json* o) {
          return o->contains("divergence") && (*o)["divergence"]["kind"] == "not_converged";
        });
    if (witness) {
      (*r)["cause"] = "integrator";
      (*r)["cause_detail"] = describe(*r) + "; but " + describe(*witness);
    } else if (others.empty() || newton_only_unconverged) {
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

namespace {

json stability_verdicts(const json& runs) {
  // Per method: the paper's claim (stable everywhere) held or not, and why not.
  std::map<std::string, json> by_method;
  for (const json& r : runs) {
    json& v = by_method[r["method"].get<std::string>()];
    if (v.is_null())
      v = {{"runs", 0},
           {"not_stable", json::array()},
           {"method_caused", 0},
           {"integrator_caused", 0}};
    v["runs"] = v["runs"].get<int>() + 1;
    if (r["status"] == "stable") continue;
    v["not_stable"].push_back({{"scene", r["scene"]},
                               {"integrator", r["integrator"]},
                               {"dt", r["dt"]},
                               {"status", r["status"]},
                               {"cause", r["cause"]}});
    if (r["cause"] == "method") v["method_caused"] = v["method_caused"].get<int>() + 1;
    if (r["cause"] == "integrator") v["integrator_caused"] = v["integrator_caused"].get<int>() + 1;
  }
  json out = json::object();
  for (auto& [method, v] : by_method) {
    const int by_method_count = v["method_caused"], by_integrator = v["integrator_caused"];
    v["verdict"] = v["not_stable"].empty() ? "stable in every run"
                   : by_method_count > 0
                       ? "fails by itself in some scene (under both integrators, at both steps)"
                   : by_integrator > 0 ? "stable once the integrator is: every failure goes with "
                                         "the linearly implicit step or the larger dt"
                                       : "failures without an attributable cause";
    out[method] = v;
  }
  return out;
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
         "diverged: NaN/inf, a lost factorization or |u| > blowup_factor x diagonal; "
         "flutter: max or RMS rotation change per step above its threshold; stuck: more than "
         "stuck_inverted_share of the elements inverted at the end of the hold (a body that did "
         "not recover); stable otherwise"}}},
      {"ramp_steps", config.stability_ramp()},
      {"hold_steps", config.stability_hold()},
      {"size", size_name(config.stability_size())},
      {"runs", json::array()},
      {"poses", json::array()}};
  out["scenes"] = json::object();
  out["surfaces"] = json::object();
  for (const std::string& id : config.stability_scenes()) {
    const json scene = stability_scene(id, config.stability_size(), config.stability_ramp(),
                                       config.stability_hold(), config.models_dir);
    out["scenes"][id] = scene;
    for (const auto& [method_id, method_name] : kRotationMethods.entries) {
      if (method_id == RotationMethod::None) continue;
      const std::string method = method_name;
      std::vector<json> group;
      const auto run = [&](const StabilityRun& spec) {
        if (config.progress)
          *config.progress << "report: stability: " << id << ": " << method << ", "
                           << kIntegrators.name(spec.integrator) << ", dt 0.01/" << spec.refinement
                           << std::endl;
        json pose;
        const auto vtu_dir =
            config.vtu && spec.refinement == 1
                ? config.out_dir / "vtu" / id / (method + "-" + kIntegrators.name(spec.integrator))
                : std::filesystem::path();
        group.push_back(run_stability_case(scene, id, spec, config.stability_ramp(),
                                           config.stability_hold(),
                                           spec.refinement == 1 ? &pose : nullptr, vtu_dir));
        if (!pose.is_null()) {
          // The rest surface is the scene's, the same for every run: stored once.
          if (!out["surfaces"].contains(id))
            out["surfaces"][id] = {{"rest_points", pose["rest_points"]},
                                   {"triangles", pose["triangles"]}};
          pose.erase("rest_points");
          pose.erase("triangles");
          out["poses"].push_back(std::move(pose));
        }
      };
      for (const Integrator integrator : {Integrator::LinearImplicit, Integrator::Newton})
        run({method_id, integrator, 1});
      // The smaller step decides the cause of a run that is not stable; where both integrators
      // are stable at dt there is nothing to attribute, and only the full report runs it anyway.
      // The smoke report (seconds, for the report's own tests) never does.
      const bool all_stable = std::all_of(group.begin(), group.end(),
                                          [](const json& r) { return r["status"] == "stable"; });
      if (config.mode == ReportConfig::Mode::Full ||
          (!all_stable && config.mode == ReportConfig::Mode::Quick))
        for (const Integrator integrator : {Integrator::LinearImplicit, Integrator::Newton})
          run({method_id, integrator, 2});
      std::vector<json*> members;
      for (json& r : group) members.push_back(&r);
      attribute_causes(members);
      for (json& r : group) out["runs"].push_back(std::move(r));
    }
  }
  out["verdicts"] = stability_verdicts(out["runs"]);
  return out;
}

}  // namespace corofem
