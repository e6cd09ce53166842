#include "report/report_driver.hpp"

#include <chrono>
#include <cstdlib>
#include <ostream>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "core/build_info.hpp"
#include "core/threads.hpp"
#include "io/run_context.hpp"
#include "report/report_checkpoint.hpp"
#include "report/report_section.hpp"

#ifndef COROFEM_SOURCE_DIR
#define COROFEM_SOURCE_DIR "."
#endif

namespace corofem {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json header(const ReportConfig& config, const std::string& label) {
  return {{"producer", "corofem report (" + label + ")"},
          {"context", run_context()},
          {"parameters",
           {{"mode", config.mode_name()},
            {"models_dir", config.with_models() ? config.models_dir.string() : ""},
            {"scenes", config.with_models() ? "bunny, horse, dragon surfaces"
                                            : "embedded procedural scenes"}}}};
}

/// The record: what produced it (header) and its body's fields.
json with_header(const ReportConfig& config, const std::string& label, json body) {
  json record = header(config, label);
  for (auto& [key, value] : body.items()) record[key] = std::move(value);
  return record;
}

fs::path write_record(const ReportConfig& config, const std::string& file, const json& record) {
  const fs::path path = config.out_dir / file;
  write_file_atomically(path, [&](std::ostream& o) { o << record.dump(1) << '\n'; });
  if (config.progress) *config.progress << "report: wrote " << path.string() << std::endl;
  return path;
}

/// Runs a section; writes its record, with what produced it and how long it took, and the records
/// it made beside it.
void write_section(const ReportConfig& config, const ReportSectionTraits& section,
                   std::vector<fs::path>& written) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<ReportRecord> beside;
  json body = section.run(config, beside);
  if (!body.is_object())
    throw std::logic_error("report section '" + section.name + "' returned a JSON " +
                           body.type_name() + " as its record, not an object");
  json record = with_header(config, section.label, std::move(body));
  record["elapsed_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  written.push_back(write_record(config, section.file, record));
  for (ReportRecord& r : beside)
    written.push_back(
        write_record(config, r.file, with_header(config, r.label, std::move(r.body))));
}

/// What a resumed report must share with the killed one: the options that choose its work, the
/// threads (the bits of a unit depend on nothing else) and the build.
json checkpoint_parameters(const ReportConfig& config) {
  json sections = json::array();
  for (const std::string& name : report_section_names())
    if (config.runs(name)) sections.push_back(name);
  return {{"mode", config.mode_name()}, {"models_dir", config.models_dir.string()},
          {"only", config.only},        {"sections", sections},
          {"vtu", config.vtu},          {"threads", thread_count()},
          {"commit", build_commit()}};
}

}  // namespace

std::vector<fs::path> run_report(const ReportConfig& given) {
  fs::create_directories(given.out_dir);
  ReportConfig config = given;
  ReportCheckpoint checkpoint(config.out_dir, checkpoint_parameters(config), config.resume);
  config.checkpoint = &checkpoint;
  std::vector<fs::path> written;
  for (const std::string& name : report_section_names()) {
    if (!config.runs(name)) continue;
    const ReportSectionTraits& section = report_section(name);
    if (checkpoint.section_done(name)) {
      if (config.progress)
        *config.progress << "report: " << name << ": " << section.file
                         << " kept from the interrupted run" << std::endl;
      written.push_back(config.out_dir / section.file);
      continue;
    }
    write_section(config, section, written);
    checkpoint.finish_section(name);
  }
  checkpoint.finish();
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
