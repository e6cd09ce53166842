#pragma once
// Tables 1 and 2 of the paper, measured here (tables.json): per model and size one row of
// real dynamic runs (energy-newton with MG-PCG, the naive Galerkin update, polar plus smoothing,
// CHOLMOD, small strain, Jacobi-PCG), with the paper's row beside it and the oracle checks.
#include <nlohmann/json.hpp>

#include "report/report_config.hpp"
#include "report/report_section.hpp"

namespace corofem {

/// The paper's Table 1 row (rotate, assemble, update, update_naive, solve ms; tps; tets,
/// vertices, levels) and Table 2 tps for bunny, horse or dragon; null for anything else.
nlohmann::json paper_table1_row(const std::string& paper_model);
nlohmann::json paper_table2_tps(const std::string& paper_model);

/// {"table1": [...], "table2": [...], "small_strain": [...], "jacobi_pcg": [...],
///  "verification": [...], "settings": {...}}; every row has "completed".
nlohmann::json run_paper_tables(const ReportConfig& config);

/// The section of `corofem report` that writes tables.json (report/report_section.hpp).
ReportSectionTraits paper_tables_section();

}  // namespace corofem
