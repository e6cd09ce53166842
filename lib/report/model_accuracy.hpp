#pragma once
// How far the corotated model is from a real nonlinear code (model_accuracy.json): CalculiX NLGEOM
// (St. Venant-Kirchhoff, total Lagrangian, C3D4) on the same meshes, supports and load vectors,
// against every rotation method's static Newton solve; and corofem's linear solve against
// CalculiX's linear one (which must agree to CalculiX's printed digits).
#include <nlohmann/json.hpp>

#include "report/report_config.hpp"
#include "report/report_section.hpp"

namespace corofem {

/// {"cases": [...]} for model_accuracy_ids() at two sizes (quick: the small one; smoke: the small
/// cantilever), or
/// {"skipped": why} without ccx.
nlohmann::json run_model_accuracy(const ReportConfig& config);

/// The section of `corofem report` that writes model_accuracy.json (report/report_section.hpp).
ReportSectionTraits model_accuracy_section();

}  // namespace corofem
