#pragma once
// Stability where methods fail (stability.json): every rotation extractor on scenes built to
// break them (report/scene_catalogue.hpp), loaded, then held, under both integrators (the paper's
// linearly implicit Euler and fully implicit Euler by Newton) at two step sizes. Per run: flutter
// (per-element rotation change per step during the settled part of the hold), kinetic energy,
// inversions, the end's equilibrium residual, divergence (NaN, a lost factorization, a Newton step
// that misses its tolerance or a blow-up stops the run and the study goes on), the energy balance
// over the hold, the asymmetry of the element force Jacobians at the end (0: conservative), and for
// every run that is not stable its cause: "integrator" when the method is stable under the other
// integrator or at the smaller step, else from the same method under Newton at dt/4 (the refined
// reference): "method" when it fails there too, "scene" for motion it shows too (and no other
// method settles), "integrator" for flutter it does not show. Newton is robust: a line search on
// the incremental potential where the force has one, and steps cut to dt/2 where it does not
// converge (integrate/implicit_euler.hpp).
#include <nlohmann/json.hpp>
#include <vector>

#include "core/types.hpp"
#include "report/report_config.hpp"
#include "report/report_section.hpp"
#include "rotation/rotation_method.hpp"
#include "scene/analysis_settings.hpp"

namespace corofem {

/// Status thresholds (rad per step, over the second half of the hold). In these scenes a settled
/// body's elements turn by less than 1e-3 rad per step (the exact minimizer's runs show it), so a
/// largest change above 0.1 rad (5.7 degrees) per step, or an RMS above 0.01, is no physical
/// motion.
struct FlutterThresholds {
  double max_rad = 0.1;
  double rms_rad = 0.01;
  double blowup_factor = 100;  ///< diverged when some |u| exceeds this times the body's diagonal
  /// The displacement beyond which a run of the body at `rest` has diverged: blowup_factor times
  /// its bounding box's diagonal.
  double blowup_displacement(const std::vector<Vec3>& rest) const;
  /// stuck when more than this share of the elements is still inverted at the end of the hold
  /// (a crumpled body keeps a third of its elements inverted; two inverted slivers of a stretched
  /// model's 33k tets are not a body that failed to recover).
  double stuck_inverted_share = 0.01;
};

/// One run: a method under an integrator at a step size.
struct StabilityRun {
  RotationMethod method;
  Integrator integrator = Integrator::LinearImplicit;
  int refinement = 1;  ///< dt = 0.01 / refinement, ramp and hold refinement x as many steps
};

/// One run of one scene; `scene` is a stability_scene() built for ramp_steps and hold_steps (at
/// its own dt; refined here by spec.refinement). `pose`, if given, receives the final boundary
/// positions colored by the largest rotation change per vertex.
nlohmann::json run_stability_case(const nlohmann::json& scene, const std::string& scene_id,
                                  const StabilityRun& spec, int ramp_steps, int hold_steps,
                                  nlohmann::json* pose = nullptr,
                                  const std::filesystem::path& vtu_dir = {});

/// Whether some run of the group (one scene and method) is not stable and no stable run at its
/// step or a smaller one explains it: its cause needs the refined reference.
bool needs_refined_reference(const std::vector<nlohmann::json>& group);

/// Sets "cause" (and "cause_detail") of every run of one scene and method that is not stable:
/// "integrator" if a run under the other integrator at the same step or at a smaller step is
/// stable; otherwise from `reference`, the method under Newton at dt/4 (the scene refined in
/// time): "method" where it blows up or stays inverted too, "scene" for flutter whose rate of
/// motion (rad/s) it shows at least half of (physical motion, not numerical), "integrator" for
/// other flutter (it converges away under refinement) and where Newton cannot solve its steps.
/// Without a reference (the smoke report): "method" if the group's other runs fail too, null (with
/// the reason) when there are none or they failed only because Newton did not converge.
void attribute_causes(std::vector<nlohmann::json*>& group,
                      const nlohmann::json* reference = nullptr);

/// After every method has run `scene`: a run of cause "scene" gets status "motion" (physical
/// motion, not numerical flutter), or, where another method is stable under the same integrator at
/// the same step (the scene can be settled), cause "method" and stays "flutter". Where no run of
/// the scene is stable (no method under either integrator at any step settles it), every failure
/// not confirmed as the method's (a blow-up, a body left inverted) gets cause "scene".
void attribute_scene_causes(nlohmann::json& runs, const std::string& scene);

/// The refined reference's step: dt / kReferenceRefinement, under Newton.
inline constexpr int kReferenceRefinement = 4;

/// How one method's runs on one scene are made.
struct MethodPlan {
  int ramp_steps = 0, hold_steps = 0;  ///< at dt
  bool smaller_step = true;            ///< dt/2 runs where some dt run is not stable
  bool smaller_step_always = false;    ///< dt/2 runs even where both dt runs are stable
  bool refined_reference = true;       ///< Newton at dt/4 where nothing else explains a failure
  std::ostream* progress = nullptr;
  std::string progress_prefix{};    ///< begins each progress line
  std::filesystem::path vtu_dir{};  ///< frames of the dt runs below it; empty: none
};

/// The runs of one method on one scene: both integrators at dt, at dt/2 and the refined reference
/// as the plan says, with their causes (attribute_causes; the scene-wide pass is the caller's).
struct MethodRuns {
  std::vector<nlohmann::json> runs;
  nlohmann::json reference;           ///< null where none was needed
  std::vector<nlohmann::json> poses;  ///< of the dt runs
};
MethodRuns run_method_on_scene(const nlohmann::json& scene, const std::string& scene_id,
                               RotationMethod method, const MethodPlan& plan);

/// {"thresholds", "runs": [...], "surfaces": {scene: rest boundary}, "poses": [...]} for
/// config.stability_scenes() x every extractor; a pose is a run's boundary at the end (dt runs).
nlohmann::json run_stability_study(const ReportConfig& config);

/// Moves what only the charts draw out of a study: {"series": each run's per-step series, in the
/// order of study["runs"], "poses", "surfaces"}. The study keeps its measurements and verdicts,
/// a record small enough to review (the quick study's series and poses are 5 MB).
nlohmann::json take_stability_frames(nlohmann::json& study);

/// The section of `corofem report` that writes stability.json (report/report_section.hpp).
ReportSectionTraits stability_section();

}  // namespace corofem
