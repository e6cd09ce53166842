#pragma once
// Stability where methods fail (stability.json): every rotation extractor on scenes built to
// break them (report/scene_catalogue.hpp), loaded, then held. Per run: flutter (per-element
// rotation change per step during the settled part of the hold), kinetic energy, inversions, the
// end's equilibrium residual, and divergence (NaN, a lost factorization or a blow-up stops the run
// and the study goes on with the next method).
#include <nlohmann/json.hpp>

#include "report/report_config.hpp"

namespace corofem {

/// Status thresholds (rad per step, over the second half of the hold). In these scenes a settled
/// body's elements turn by less than 1e-3 rad per step (the exact minimizer's runs show it), so a
/// largest change above 0.1 rad (5.7 degrees) per step, or an RMS above 0.01, is no physical motion.
struct FlutterThresholds {
  double max_rad = 0.1;
  double rms_rad = 0.01;
  double blowup_factor = 100;  ///< diverged when some |u| exceeds this times the body's diagonal
};

/// One run of one scene with one extractor; `scene` is a stability_scene(). `poses`, if given,
/// receives the final boundary positions colored by the largest rotation change per vertex.
nlohmann::json run_stability_case(const nlohmann::json& scene, const std::string& scene_id,
                                  const std::string& method, int ramp_steps, int hold_steps,
                                  nlohmann::json* pose = nullptr,
                                  const std::filesystem::path& vtu_dir = {});

/// {"thresholds", "runs": [...], "poses": [...]} for config.stability_scenes() x every extractor.
nlohmann::json run_stability_study(const ReportConfig& config);

}  // namespace corofem
