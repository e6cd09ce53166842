#pragma once
// What `corofem report` runs: sections, sizes and step counts per mode.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "report/scene_catalogue.hpp"

namespace corofem {

class ReportCheckpoint;

struct ReportConfig {
  /// standard (the default, the main job): Table 1 at the paper's three sizes and small versions
  /// of every other section, about 5 minutes on 2 cores; full: every table and sweep at the
  /// paper's sizes and the stability study at its full length (about an hour); quick: small
  /// versions of every section (about 5 minutes); smoke: seconds-long, for the tests of the
  /// report itself.
  enum class Mode { Standard, Full, Quick, Smoke } mode = Mode::Standard;
  std::filesystem::path out_dir = "out/report";
  std::filesystem::path models_dir;  ///< empty: procedural scenes only
  /// The sections to run, by name (report/report_section.hpp); empty: every registered one.
  std::vector<std::string> sections;
  bool vtu = false;  ///< stability: VTU frames for ParaView
  std::string only;  ///< if set: just the models / stability scenes of this name
  std::ostream* progress = nullptr;
  /// --resume: take what a killed report into out_dir had finished (report/report_checkpoint.hpp).
  bool resume = false;
  /// Where the sections keep each finished unit; set by run_report for the sections it runs.
  ReportCheckpoint* checkpoint = nullptr;

  std::string mode_name() const;
  bool runs(const std::string& section) const;
  bool with_models() const { return !models_dir.empty(); }
  /// The table models (procedural, or the files' with --models) and the sizes of each.
  std::vector<std::string> models() const;  ///< quadruped first: the paper's rows
  std::vector<SceneSize> table_sizes(const std::string& model) const;
  /// Whether the rival solvers' table (and the Jacobi-PCG table, see jacobi_table) runs at this
  /// size: in the standard report only up to the paper's smallest size, where it costs seconds.
  bool comparison_tables(SceneSize size) const;
  /// Whether the Jacobi-PCG table runs at this size: as the comparison tables, and on every model
  /// file with --models, on whose horse and dragon multigrid must beat Jacobi-PCG (seconds a
  /// model; the rival solvers' minutes stay out of the standard report).
  bool jacobi_table(SceneSize size) const;
  /// Sizes past the tables' at which only the multigrid quality rows run: the quadruped at 270k
  /// in the full report, so its sizes show whether rho and iterations stay flat.
  std::vector<SceneSize> multigrid_only_sizes(const std::string& model) const;
  int table_warmup() const;
  int table_measured() const;  ///< steps in each median (at least 20 outside smoke)
  /// Steps in the median of Table 1's CHOLMOD row: 5 in the standard report. Its factorization,
  /// most of its step, does the same flops every step (the same pattern), and costs 0.45 s a
  /// step on quadruped-67k. (The naive update's row keeps the main run's steps: its update phase
  /// refactors the coarsest level when the operator has moved, which depends on the state; on
  /// twisting-bar-small its median was 5x lower over the first 5 measured steps.)
  int table_cholmod_measured() const;
  double default_tolerance() const { return 1e-4; }  ///< MG-PCG relative residual per step
  SceneSize sweep_size(const std::string& model) const;
  std::vector<SceneSize> resolution_sizes() const;
  int sweep_steps() const;
  SceneSize stability_size() const { return SceneSize::Small; }
  int stability_ramp() const;
  int stability_hold() const;
  /// The catalogue's stability scenes (report/scene_catalogue.hpp); outside --full without
  /// those it runs only at full length (stability_scene_full_only), which --only still names.
  std::vector<std::string> stability_scenes() const;
};

}  // namespace corofem
