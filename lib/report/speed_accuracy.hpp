#pragma once
// Speed against accuracy (speed_accuracy.json): per scene, sweeps of solver settings, rotation
// methods and mesh resolution; time per step against error, the Pareto front, and the cheapest
// setting and coarsest resolution that meet the stated tolerances.
#include <nlohmann/json.hpp>

#include "report/report_config.hpp"
#include "report/report_section.hpp"

namespace corofem {

/// Errors a setting must stay under to "meet" the scene's needs.
struct AccuracyTargets {
  double solver = 1e-3;      ///< |u - u_cholmod| / |u_cholmod| at the last step, same resolution
  double rotation = 1e-3;    ///< |u - u_exact| / |u_exact| against energy-exact + CHOLMOD
  double resolution = 0.05;  ///< probe displacement against the finest resolution
};

/// Marks "pareto" on the completed, non-reference points of `sweep` (every sweep if empty): true
/// where no other such point of the same sweep beats it in both time and error (false on the
/// completed reference points).
void mark_pareto_front(nlohmann::json& points, const std::string& sweep = "");

nlohmann::json run_speed_accuracy(const ReportConfig& config);

/// The section of `corofem report` that writes speed_accuracy.json (report/report_section.hpp).
ReportSectionTraits speed_accuracy_section();

}  // namespace corofem
