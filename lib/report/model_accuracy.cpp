#include "report/model_accuracy.hpp"

#include <chrono>
#include <ostream>

#include "core/threads.hpp"
#include "integrate/static_solver.hpp"
#include "linalg/linear_solver.hpp"
#include "report/calculix_oracle.hpp"
#include "report/case_record.hpp"
#include "report/report_checkpoint.hpp"
#include "report/section_progress.hpp"
#include "report/units_side_by_side.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene.hpp"
#include "scene/scene_problem.hpp"

namespace corofem {
using nlohmann::json;

namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// |a - b| / |b| (L2 over every DOF) and max |a - b| / max |b|.
json errors(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return {{"l2", finite_or_null((a - b).norm() / b.norm())},
          {"max", finite_or_null((a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff())}};
}

json run_case(const std::string& id, SceneSize size, const ReportConfig& config,
              std::ostream* progress, const std::string& progress_prefix) {
  const json scene_json = model_accuracy_scene(id, size);
  const Scene scene = parse_scene(scene_json, ".", id);
  const AnalysisSpec& a = scene.analysis;
  FeProblem problem = build_problem(scene);
  const auto work_dir = config.out_dir / "calculix" / (id + "-" + size_name(size));
  json out = {{"scene", id},
              {"size", size_name(size)},
              {"tets", problem.mesh.num_tets()},
              {"vertices", problem.mesh.num_vertices()},
              {"scene_json", scene_json}};
  auto start = std::chrono::steady_clock::now();
  const Eigen::VectorXd ccx_linear = run_calculix(problem, false, work_dir, "linear", a.load_steps);
  out["calculix_ms"]["linear"] = elapsed_ms(start);
  start = std::chrono::steady_clock::now();
  const Eigen::VectorXd ccx_nlgeom = run_calculix(problem, true, work_dir, "nlgeom", a.load_steps);
  out["calculix_ms"]["nlgeom"] = elapsed_ms(start);
  out["displacement_max_m"] = ccx_nlgeom.cwiseAbs().maxCoeff();
  auto solver = make_cholmod_solver(a.factorization);
  IdentityExtractor none;
  StaticOptions newton{true, a.load_steps, a.tolerance, a.max_iterations, true};
  newton.factorization = a.factorization;  // its tangent's (the linear solve's is the solver's)
  const SimulationResult linear =
      solve_static(problem, none, *solver, {false, 1, a.tolerance, 1, false});
  out["linear"] = {{"against_calculix_linear", errors(linear.displacement, ccx_linear)},
                   {"against_calculix_nlgeom", errors(linear.displacement, ccx_nlgeom)}};
  out["methods"] = json::array();
  for (RotationMethod method : rotation_methods()) {
    if (!method.traits().compared) continue;
    const std::string& name = method.name();
    if (progress) *progress << progress_prefix << ": " << name << std::endl;
    out["methods"].push_back(record_case({{"method", name}}, [&] {
      auto rotation = make_rotation_extractor(method, problem.mesh, a.rotation_params);
      const auto t0 = std::chrono::steady_clock::now();
      const SimulationResult r = solve_static(problem, *rotation, *solver, newton);
      return json{{"converged", r.converged},
                  {"newton_iterations", r.iterations},
                  {"residual", r.residual},
                  {"solve_ms", elapsed_ms(t0)},
                  {"against_calculix_nlgeom", errors(r.displacement, ccx_nlgeom)}};
    }));
  }
  return out;
}

}  // namespace

json run_model_accuracy(const ReportConfig& config) {
  if (!calculix_available()) return {{"skipped", "ccx (Debian calculix-ccx) is not on PATH"}};
  // Two resolutions in the full report; the small one in --quick and --smoke (Newton's sparse LU
  // takes 20-60 s per method at 11k tets).
  const std::vector<SceneSize> sizes = config.mode == ReportConfig::Mode::Full
                                           ? std::vector<SceneSize>{SceneSize::Small, SceneSize::S}
                                           : std::vector<SceneSize>{SceneSize::Small};
  json out = {
      {"oracle", "CalculiX ccx, C3D4, *STATIC with NLGEOM (St. Venant-Kirchhoff) and without"},
      {"errors", "l2: |u - u_ccx| / |u_ccx| over every DOF; max: max |u - u_ccx| / max |u_ccx|"},
      {"cases", json::array()}};
  std::vector<std::pair<std::string, SceneSize>> cases;
  for (const std::string& id : model_accuracy_ids())
    if ((config.mode != ReportConfig::Mode::Smoke || id == "cantilever") &&
        (config.only.empty() || config.only == id))
      for (SceneSize size : sizes) cases.emplace_back(id, size);
  const int count = static_cast<int>(cases.size());
  SectionProgress progress(config.progress, "model accuracy", count);
  // The cases side by side (their CalculiX runs too), the quadruped, the longest, first.
  std::vector<json> results(cases.size());
  run_units_side_by_side(count, thread_count(), config.progress, [&](int k, std::ostream* lines) {
    const auto& [id, size] = cases[static_cast<std::size_t>(k)];
    const std::string name = id + " " + size_name(size);
    const std::string prefix = progress.begin(name);
    results[static_cast<std::size_t>(k)] = report_unit(  // a unit, kept for --resume
        config, "model-accuracy", name,
        [&] {
          return record_case({{"scene", id}, {"size", size_name(size)}},
                             [&] { return run_case(id, size, config, lines, prefix); });
        },
        prefix);
    progress.finish();
  });
  for (json& result : results) out["cases"].push_back(std::move(result));
  return out;
}

ReportSectionTraits model_accuracy_section() {
  return {"model-accuracy", "model accuracy", "model_accuracy.json",
          "every rotation extractor's static solve against CalculiX NLGEOM on the same\n"
          "meshes and loads, and the linear solve against CalculiX's (needs ccx)",
          [](const ReportConfig& config, std::vector<ReportRecord>&) {
            return run_model_accuracy(config);
          }};
}

}  // namespace corofem
