#include "report/stability_study.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>

#include "core/errors.hpp"
#include "fem/corotated_system.hpp"
#include "report/case_record.hpp"
#include "report/timed_run.hpp"
#include "report/vtu_writer.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {
using nlohmann::json;

namespace {

/// Thrown by the step observer when the displacement leaves any physical range.
struct BlowUp : NumericalFault {
  using NumericalFault::NumericalFault;
};

/// Vertices on the boundary (on a face that belongs to one tet only).
std::vector<int> boundary_vertices(const TetMesh& mesh) {
  std::map<std::array<int, 3>, int> faces;
  for (const Tet& t : mesh.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != skip) f[k++] = t[a];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  std::vector<char> on(mesh.rest.size(), 0);
  for (const auto& [f, count] : faces)
    if (count == 1)
      for (int v : f) on[v] = 1;
  std::vector<int> out;
  for (std::size_t v = 0; v < on.size(); ++v)
    if (on[v]) out.push_back(static_cast<int>(v));
  return out;
}

double round4(double x) { return std::isfinite(x) ? std::round(x * 1e4) / 1e4 : 0.0; }

}  // namespace

json run_stability_case(const json& scene, const std::string& scene_id, const std::string& method,
                        int ramp_steps, int hold_steps, json* pose, const std::filesystem::path& vtu_dir) {
  const FlutterThresholds thresholds;
  json s = scene;
  s["analysis"]["rotation"] = method;
  const int settle_from = ramp_steps + hold_steps / 2;  // the settled half of the hold
  std::vector<double> rms_series, max_series, energy_series;
  std::vector<int> inverted_series;
  std::vector<Mat3> previous;
  std::vector<double> vertex_change;  // largest change per vertex in the settled window
  double flutter_rms_sum = 0, flutter_max = 0;
  long long flutter_samples = 0;
  int last_step = 0;
  double diagonal = 0;
  json record = {{"scene", scene_id}, {"method", method}, {"ramp_steps", ramp_steps}, {"hold_steps", hold_steps}};
  TimedRun run;
  TimedRunOptions options;
  options.on_step = [&](const StepState& st, const FeProblem& problem) {
    last_step = st.step;
    if (diagonal == 0) {
      Vec3 lo = problem.mesh.rest[0], hi = lo;
      for (const Vec3& x : problem.mesh.rest) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      diagonal = (hi - lo).norm();
      vertex_change.assign(problem.mesh.rest.size(), 0.0);
    }
    const int tets = problem.mesh.num_tets();
    double sum2 = 0, largest = 0;
    if (!previous.empty()) {
      for (int e = 0; e < tets; ++e) {
        const double d = angle_between(st.rotations[e], previous[e]);
        sum2 += d * d;
        largest = std::max(largest, d);
        if (st.step > settle_from)
          for (int v : problem.mesh.tets[e]) vertex_change[v] = std::max(vertex_change[v], d);
      }
    }
    previous = st.rotations;
    const double rms = std::sqrt(sum2 / tets);
    rms_series.push_back(rms);
    max_series.push_back(largest);
    if (st.step > settle_from) {
      flutter_rms_sum += sum2;
      flutter_samples += tets;
      flutter_max = std::max(flutter_max, largest);
    }
    energy_series.push_back(0.5 * st.velocity.cwiseProduct(st.velocity).dot(problem.mass));
    inverted_series.push_back(count_inverted(problem, problem.positions(st.displacement)));
    if (st.displacement.lpNorm<Eigen::Infinity>() > thresholds.blowup_factor * diagonal)
      throw BlowUp("displacement beyond " + std::to_string(thresholds.blowup_factor) +
                   "x the body's diagonal at step " + std::to_string(st.step));
    if (!vtu_dir.empty() && (st.step % 10 == 0)) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.vtu", st.step);
      std::filesystem::create_directories(vtu_dir);
      write_vtu(vtu_dir / name, problem.mesh, st.displacement, st.rotations);
    }
  };
  json result = record_case(record, [&] {
    run = timed_run(s, scene_id, options);
    return json::object();
  });
  // A numerical fault (NaN, a lost factorization, a blow-up) is the measurement "diverged"; bad
  // input or an internal error means the case did not run.
  const bool diverged = !result["completed"].get<bool>() && result["error"]["kind"] == "numerical";
  if (!result["completed"].get<bool>() && !diverged) {
    record["completed"] = false;
    record["error"] = result["error"];
    record["status"] = "failed";
    return record;
  }
  record["completed"] = true;
  record["status"] = diverged ? "diverged"
                     : (flutter_max > thresholds.max_rad ||
                        (flutter_samples > 0 && std::sqrt(flutter_rms_sum / flutter_samples) > thresholds.rms_rad))
                         ? "flutter"
                         : "stable";
  record["diverged_step"] = diverged ? json(last_step + 1) : json(nullptr);
  if (diverged) record["divergence"] = result["error"];
  record["flutter_rms_rad"] = flutter_samples > 0 && !diverged ? json(std::sqrt(flutter_rms_sum / flutter_samples)) : json(nullptr);
  record["flutter_max_rad"] = flutter_samples > 0 && !diverged ? json(flutter_max) : json(nullptr);
  record["inverted_max"] = inverted_series.empty() ? 0 : *std::max_element(inverted_series.begin(), inverted_series.end());
  record["inverted_final"] = inverted_series.empty() ? 0 : inverted_series.back();
  record["kinetic_energy_final"] = energy_series.empty() ? json(nullptr) : finite_or_null(energy_series.back());
  record["residual_final"] = diverged ? json(nullptr) : finite_or_null(run.result.residual);
  record["steps_run"] = last_step;
  record["tets"] = run.tets;
  record["series"] = {{"rotation_change_rms_rad", rms_series},
                      {"rotation_change_max_rad", max_series},
                      {"kinetic_energy", energy_series},
                      {"inverted", inverted_series}};
  if (pose && !diverged) {
    json points = json::array(), values = json::array();
    for (int v : boundary_vertices(run.mesh)) {
      const Vec3 x = run.mesh.rest[v] + run.result.displacement.segment<3>(3 * v);
      points.push_back({round4(x.x()), round4(x.y()), round4(x.z())});
      values.push_back(round4(vertex_change[v]));
    }
    *pose = {{"scene", scene_id}, {"method", method}, {"points", points}, {"rotation_change_max_rad", values}};
  }
  return record;
}

json run_stability_study(const ReportConfig& config) {
  const FlutterThresholds thresholds;
  json out = {{"thresholds",
               {{"flutter_max_rad", thresholds.max_rad},
                {"flutter_rms_rad", thresholds.rms_rad},
                {"blowup_factor", thresholds.blowup_factor},
                {"window", "second half of the hold (loads constant)"},
                {"statuses", "diverged: NaN/inf, a lost factorization or |u| > blowup_factor x diagonal; "
                             "flutter: max or RMS rotation change per step above its threshold; stable otherwise"}}},
              {"ramp_steps", config.stability_ramp()},
              {"hold_steps", config.stability_hold()},
              {"size", size_name(config.stability_size())},
              {"runs", json::array()},
              {"poses", json::array()}};
  out["scenes"] = json::object();
  for (const std::string& id : config.stability_scenes()) {
    const json scene = stability_scene(id, config.stability_size(), config.stability_ramp(),
                                       config.stability_hold(), config.models_dir);
    out["scenes"][id] = scene;
    for (const std::string& method : rotation_method_names()) {
      if (method == "none") continue;
      if (config.progress) *config.progress << "report: stability: " << id << ": " << method << std::endl;
      json pose;
      const auto vtu_dir = config.vtu ? config.out_dir / "vtu" / id / method : std::filesystem::path();
      json run = run_stability_case(scene, id, method, config.stability_ramp(), config.stability_hold(),
                                    &pose, vtu_dir);
      out["runs"].push_back(run);
      if (!pose.is_null()) out["poses"].push_back(pose);
    }
  }
  return out;
}

}  // namespace corofem
