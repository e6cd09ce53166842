#pragma once
// `corofem report`: runs the sections a config asks for, writes their JSON records (tables.json,
// speed_accuracy.json, stability.json) atomically into the output folder, then draws REPORT.md
// and the charts from the JSON alone (reports/render_report.py).
#include "report/report_config.hpp"

namespace corofem {

/// Runs and writes the sections; returns the paths written. Failing cases are recorded in the
/// JSON ("completed": false), they do not abort the report. With config.resume, takes the
/// sections and units a killed report into the same folder had finished
/// (report/report_checkpoint.hpp).
std::vector<std::filesystem::path> run_report(const ReportConfig& config);

/// Draws REPORT.md and the charts of `dir` from its JSON with the renderer script (found beside
/// the sources this binary was built from, or $COROFEM_RENDERER); Rendering::Tune: the chart of
/// `corofem tune` (pareto.png from tune.json). Returns the script's exit code (127 when no
/// renderer is found).
enum class Rendering { Report, Tune };
int render_report(const std::filesystem::path& dir, std::ostream* progress,
                  Rendering what = Rendering::Report);

}  // namespace corofem
