// A report section of one's own: Table 1's phases for the example's rotation method and smoother
// beside the paper's method, on the report's table scenes (lib/docs/extending.md). Its renderer
// unit is report_sections/own_methods.py.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "own_method.hpp"
#include "report/case_record.hpp"
#include "report/report_checkpoint.hpp"
#include "report/report_section.hpp"
#include "report/scene_catalogue.hpp"
#include "report/timed_run.hpp"

namespace own {
namespace {

using nlohmann::json;

/// The variants of a row: the paper's method, then each of the example's methods, then both.
std::vector<std::pair<std::string, json>> variants() {
  return {{"paper's method", json::object()},
          {"own rotation", {{"rotation", kEnergyMueller}}},
          {"own smoother", {{"smoother", kDampedL1Jacobi}}},
          {"both", {{"rotation", kEnergyMueller}, {"smoother", kDampedL1Jacobi}}}};
}

/// One variant of `scene` timed as Table 1 times it; its displacement against `paper` (the
/// paper's method's final displacement; empty for the paper's method itself).
json run_variant(json scene, const json& analysis, const std::string& name, int warmup,
                 const Eigen::VectorXd& paper, Eigen::VectorXd& displacement) {
  scene["analysis"].update(analysis);
  const corofem::TimedRun run = corofem::timed_run(scene, name, {.warmup_steps = warmup});
  json row;
  for (const char* phase : {"rotate", "assemble", "update", "solve", "step"})
    row[std::string(phase) + "_ms"] = run.median_ms(phase, warmup);
  row["linear_iterations"] = run.median_iterations(warmup);
  displacement = run.result.displacement;
  if (paper.size() == displacement.size() && paper.norm() > 0)
    row["displacement_vs_paper"] = (displacement - paper).norm() / paper.norm();
  return row;
}

/// One model's four rows: a unit of the section, kept by `report --resume` after a kill.
json model_rows(const corofem::ReportConfig& config, const std::string& model) {
  const int warmup = config.table_warmup(), steps = warmup + config.table_measured();
  const corofem::SceneSize size = config.table_sizes(model).front();  // the smallest
  const json scene =
      corofem::table_scene(model, size, steps, config.default_tolerance(), config.models_dir);
  const std::string id = model + "-" + corofem::size_name(size);
  json rows = json::array();
  Eigen::VectorXd paper;
  for (const auto& [variant, analysis] : variants()) {
    if (config.progress) *config.progress << "own methods: " << id << ", " << variant << "\n";
    Eigen::VectorXd displacement;
    rows.push_back(corofem::record_case({{"model", id}, {"variant", variant}}, [&] {
      json row = run_variant(scene, analysis, id, warmup, paper, displacement);
      row["model"] = id;
      row["variant"] = variant;
      return row;
    }));
    if (variant == "paper's method") paper = displacement;
  }
  return rows;
}

json run_own_table(const corofem::ReportConfig& config, std::vector<corofem::ReportRecord>&) {
  json rows = json::array();
  for (const std::string& model : config.models())
    for (json& row : corofem::report_unit(config, "own-methods", model,
                                          [&] { return model_rows(config, model); }))
      rows.push_back(std::move(row));
  return {{"rows", rows},
          {"methods", {{"rotation", kEnergyMueller}, {"smoother", kDampedL1Jacobi}}},
          {"warmup_steps", config.table_warmup()},
          {"measured_steps", config.table_measured()}};
}

}  // namespace

void register_own_table() {
  corofem::register_report_section(
      {"own-methods", "own methods", "own_methods.json",
       "Table 1's phases for this program's rotation method and smoother beside the\n"
       "paper's method, on the table scenes, with each variant's displacement against it",
       run_own_table});
}

}  // namespace own
