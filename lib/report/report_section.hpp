#pragma once
// A section of `corofem report` as one unit: its name (and so its flag --NAME-only), the record it
// writes, the lines of `corofem report --help` that say what the record holds, and how it runs.
// The built-ins define their traits in their own files; a user's program adds its own with
// register_report_section before it runs the report. The driver, the CLI's flags and usage and
// ci/report's flags all derive from this list; the renderer's unit for the same record file
// (reports/sections/, or a folder in $COROFEM_REPORT_SECTIONS) draws its part of REPORT.md.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "report/report_config.hpp"

namespace corofem {

/// A record a section writes beside its own (the stability study's chart frames).
struct ReportRecord {
  std::string file;   ///< in the output folder, e.g. "stability_frames.json"
  std::string label;  ///< its producer: "corofem report (<label>)"
  nlohmann::json body;
};

struct ReportSectionTraits {
  std::string name;   ///< lower case, digits and '-': "speed-accuracy" (flag --speed-accuracy-only)
  std::string label;  ///< the record's producer: "corofem report (<label>)"
  std::string file;   ///< its record in the output folder, "<something>.json"
  std::string usage;  ///< what the record holds: lines of at most 77 characters for --help
  /// Runs the section and returns its record's body (the driver adds what produced it); may add
  /// records to write beside it. A failing case belongs in the body ("completed": false).
  std::function<nlohmann::json(const ReportConfig&, std::vector<ReportRecord>& beside)> run;
};

/// Adds a section after the built-ins; std::invalid_argument for an empty or taken name, a name
/// that is no flag, a file that is not a new "*.json", or no run.
void register_report_section(ReportSectionTraits traits);
/// Every section, in the order the report runs them: the built-ins, then the registered ones.
std::vector<std::string> report_section_names();
/// The section `name`; std::out_of_range naming the registered sections for another.
const ReportSectionTraits& report_section(std::string_view name);

}  // namespace corofem
