#include "report/report_driver.hpp"

#include <chrono>
#include <cstdlib>
#include <ostream>

#include "core/atomic_file.hpp"
#include "io/run_context.hpp"
#include "report/model_accuracy.hpp"
#include "report/paper_tables.hpp"
#include "report/speed_accuracy.hpp"
#include "report/stability_study.hpp"

#ifndef COROFEM_SOURCE_DIR
#define COROFEM_SOURCE_DIR "."
#endif

namespace corofem {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json header(const ReportConfig& config, const char* section) {
  return {{"producer", std::string("corofem report (") + section + ")"},
          {"context", run_context()},
          {"parameters",
           {{"mode", config.mode_name()},
            {"models_dir", config.with_models() ? config.models_dir.string() : ""},
            {"scenes", config.with_models() ? "bunny, horse, dragon surfaces"
                                            : "embedded procedural scenes"}}}};
}

/// The record: what produced it (header) and its body's fields.
json with_header(const ReportConfig& config, const char* section, json body) {
  json record = header(config, section);
  for (auto& [key, value] : body.items()) record[key] = std::move(value);
  return record;
}

fs::path write_record(const ReportConfig& config, const char* file, const json& record) {
  const fs::path path = config.out_dir / file;
  write_file_atomically(path, [&](std::ostream& o) { o << record.dump(1) << '\n'; });
  if (config.progress) *config.progress << "report: wrote " << path.string() << std::endl;
  return path;
}

template <class F>
fs::path write_section(const ReportConfig& config, const char* section, const char* file, F&& run) {
  const auto start = std::chrono::steady_clock::now();
  json record = with_header(config, section, run());
  record["elapsed_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return write_record(config, file, record);
}

}  // namespace

std::vector<fs::path> run_report(const ReportConfig& config) {
  fs::create_directories(config.out_dir);
  std::vector<fs::path> written;
  if (config.tables)
    written.push_back(
        write_section(config, "tables", "tables.json", [&] { return run_paper_tables(config); }));
  if (config.speed_accuracy)
    written.push_back(write_section(config, "speed-accuracy", "speed_accuracy.json",
                                    [&] { return run_speed_accuracy(config); }));
  if (config.stability) {
    json frames;  // the charts' series and poses, beside the study's record
    written.push_back(write_section(config, "stability", "stability.json", [&] {
      json study = run_stability_study(config);
      frames = take_stability_frames(study);
      return study;
    }));
    written.push_back(write_record(config, "stability_frames.json",
                                   with_header(config, "stability frames", std::move(frames))));
  }
  if (config.model_accuracy)
    written.push_back(write_section(config, "model accuracy", "model_accuracy.json",
                                    [&] { return run_model_accuracy(config); }));
  return written;
}

int render_report(const fs::path& dir, std::ostream* progress, Rendering what) {
  fs::path script = fs::path(COROFEM_SOURCE_DIR) / "reports" / "render";
  if (const char* env = std::getenv("COROFEM_RENDERER")) script = env;
  std::error_code ec;
  if (!fs::exists(script, ec)) {
    if (progress) *progress << "renderer " << script.string() << " not found; JSON only\n";
    return 127;
  }
  // Paths are quoted for the shell; a quote inside them is refused rather than escaped.
  const std::string d = dir.string(), s = script.string();
  if (d.find('\'') != std::string::npos || s.find('\'') != std::string::npos) return 127;
  const std::string option = what == Rendering::Tune ? " --tune" : "";
  const int status = std::system(("'" + s + "'" + option + " '" + d + "'").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

}  // namespace corofem
