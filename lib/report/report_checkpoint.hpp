#pragma once
// `corofem report --resume`: what a killed report had finished, kept on disk as it finished, so
// that the resumed report takes it instead of running it again and ends with the records an
// uninterrupted run writes (but for times). DIR/.resume/ holds run.json (the report's parameters
// and the sections whose records are written, replaced atomically) and per section its finished
// units (a table model at a size, a sweep's scene, a stability scene and method, a model-accuracy
// case), one JSON line each, written as each unit ends. A line a kill cut short (even SIGKILL) is
// left out and its unit runs again. A report that runs to its end removes DIR/.resume/.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "report/report_config.hpp"

namespace corofem {

class ReportCheckpoint {
 public:
  /// A fresh report (resume false) starts DIR/.resume/ anew with `parameters`. A resumed one
  /// reads it; InputError when there is none (the report ended, or never began in DIR) or when
  /// its parameters differ from these (the killed run's options and build, named in the message).
  ReportCheckpoint(std::filesystem::path out_dir, nlohmann::json parameters, bool resume);
  ~ReportCheckpoint();

  /// Whether the section's records were written before the kill.
  bool section_done(const std::string& section) const { return done_.count(section) > 0; }
  /// The section's records are written.
  void finish_section(const std::string& section);
  /// The report ran to its end: DIR/.resume/ goes.
  void finish();

  /// A unit of `section`: its output as the killed run kept it, else `run`'s, kept before it is
  /// returned. Units may run in threads side by side. `kept` (if given) says which it was.
  nlohmann::json unit(const std::string& section, const std::string& name,
                      const std::function<nlohmann::json()>& run, bool* kept = nullptr);

 private:
  void write_state() const;
  std::filesystem::path dir_;
  nlohmann::json parameters_;
  std::set<std::string> done_;
  std::map<std::string, std::map<std::string, nlohmann::json>>
      kept_;  ///< section -> unit -> output
  std::mutex lock_;
};

/// A unit of `section` through config.checkpoint (run_report sets it), or `run` itself without
/// one; a kept unit says so on config.progress after `progress_prefix`.
nlohmann::json report_unit(const ReportConfig& config, const std::string& section,
                           const std::string& name, const std::function<nlohmann::json()>& run,
                           const std::string& progress_prefix = {});

}  // namespace corofem
