// corofem_tune_targets: issue 39's targets for `corofem tune`. Tunes the report's scenes, dynamic
// (the bunny, horse and dragon at their table sizes from the models folder, the quadruped at 67k)
// and static (the model-accuracy quadruped and cantilever), for targets 1e-2 and 1e-3 on the
// displacement, with the resolution free and fixed, and writes each tune.json and a summary:
// status, the re-run's error and cost against the scene as given (the report's default setting),
// runs against the full grid, and the search's wall time.
// Usage: corofem_tune_targets --out DIR [--models DIR] [--only NAME] [--budget MINUTES] [--steps N]
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "io/run_context.hpp"
#include "report/scene_catalogue.hpp"
#include "tune/scene_tuner.hpp"

namespace {
using namespace corofem;
using nlohmann::json;
namespace fs = std::filesystem;

struct Case {
  std::string name;
  json scene;
};

std::vector<Case> cases(const fs::path& models, int steps) {
  std::vector<Case> out;
  if (!models.empty())
    for (const std::string model : {"bunny", "horse", "dragon"})
      out.push_back({model, table_scene(model, file_model_size(model), steps, 1e-4, models)});
  out.push_back({"quadruped-67k", table_scene("quadruped", SceneSize::L, steps, 1e-4)});
  out.push_back({"quadruped-static", model_accuracy_scene("quadruped", SceneSize::S)});
  out.push_back({"cantilever-static", model_accuracy_scene("cantilever", SceneSize::S)});
  return out;
}

json summary(const std::string& name, const std::string& resolution, const json& r) {
  const json& a = r["answer"];
  json s = {{"scene", name},
            {"target", r["target"]},
            {"resolution", resolution},
            {"status", a["status"]},
            {"reason", a["reason"]},
            {"changes", a["changes"]},
            {"reference_error", r["reference_error"].value("value", json(nullptr))},
            {"runs", r["runs"]},
            {"full_grid_runs", r["full_grid_runs"]},
            {"search_fraction", r["search_fraction"]},
            {"elapsed_s", r["elapsed_s"]},
            {"budget_spent", r["budget_spent"]}};
  if (r.contains("given") && r["given"].value("completed", false)) {
    s["given_error"] = r["given"]["error_with_reference"];
    s["given_cost_ms"] = r["given"]["cost_ms"];
    s["given_tets"] = r["given"]["tets"];
  }
  if (a.contains("rerun") && a["rerun"].value("completed", false)) {
    s["rerun_error"] = a["rerun"]["error_with_reference"];
    s["rerun_cost_ms"] = a["rerun"]["cost_ms"];
    s["rerun_tets"] = a["rerun"]["tets"];
  }
  if (a.contains("speedup_over_given")) s["speedup_over_given"] = a["speedup_over_given"];
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path out_dir, models;
  std::string only;
  double budget = 5;
  int steps = 20;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--out"))
      out_dir = argv[i + 1];
    else if (!std::strcmp(argv[i], "--models"))
      models = argv[i + 1];
    else if (!std::strcmp(argv[i], "--only"))
      only = argv[i + 1];
    else if (!std::strcmp(argv[i], "--budget"))
      budget = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--steps"))
      steps = std::stoi(argv[i + 1]);
    else {
      std::cerr << "usage: corofem_tune_targets --out DIR [--models DIR] [--only NAME] "
                   "[--budget MINUTES] [--steps N]\n";
      return 2;
    }
  }
  if (out_dir.empty()) {
    std::cerr << "corofem_tune_targets: --out DIR is required\n";
    return 2;
  }
  try {
    fs::create_directories(out_dir);
    json record = {{"producer", "corofem_tune_targets"},
                   {"context", run_context()},
                   {"parameters", {{"budget_minutes", budget}, {"steps", steps}}},
                   {"cases", json::array()}};
    for (const Case& c : cases(models, steps)) {
      if (!only.empty() && c.name != only) continue;
      for (const bool free : {true, false})
        for (const double target : {1e-2, 1e-3}) {
          const std::string resolution = free ? "free" : "fixed";
          std::cerr << "tune_targets: " << c.name << ", target " << target << ", resolution "
                    << resolution << "\n";
          TuneOptions options;
          options.target = target;
          options.budget_minutes = budget;
          options.axes.resolution_free = free;
          options.progress = &std::cerr;
          const TuneOutcome outcome = tune_scene(c.scene, ".", c.name, options);
          const std::string file =
              c.name + "-" + resolution + "-" + (target == 1e-2 ? "1e-2" : "1e-3") + ".tune.json";
          write_file_atomically(out_dir / file,
                                [&](std::ostream& o) { o << outcome.record.dump(1) << '\n'; });
          record["cases"].push_back(summary(c.name, resolution, outcome.record));
          write_file_atomically(out_dir / "tune_targets.json",
                                [&](std::ostream& o) { o << record.dump(1) << '\n'; });
        }
    }
  } catch (const std::exception& e) {
    std::cerr << "corofem_tune_targets: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
