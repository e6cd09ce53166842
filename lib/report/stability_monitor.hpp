#pragma once
// The stability study's observer of one run: after every step it measures how far each element's
// rotation moved (the flutter of the paper's Figure 4 shows there), the energy balance over the
// hold, inverted elements, and at the end of the hold how non-conservative the method's force is;
// it stops a run that blows up, and writes VTU frames on request.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fem/fe_problem.hpp"
#include "integrate/implicit_euler.hpp"
#include "report/stability_study.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

class StabilityMonitor {
 public:
  /// Ramp steps, then hold steps (loads constant); damping coefficients of the scene; frames
  /// every 10th step into `vtu_dir` unless it is empty.
  StabilityMonitor(RotationMethod method, int ramp_steps, int hold_steps, double dt, double alpha,
                   double beta, std::filesystem::path vtu_dir);

  /// After every step (TimedRunOptions::on_step); throws NumericalFault when |u| leaves the
  /// body's diagonal times FlutterThresholds::blowup_factor.
  void observe(const StepState& step, const FeProblem& problem);

  int last_step() const { return last_step_; }
  /// Whether the settled half of the hold saw rotations move above the thresholds.
  bool flutters() const;
  /// Whether more than FlutterThresholds::stuck_inverted_share of the `tets` elements are still
  /// inverted at the last step observed (a body that did not recover).
  bool stuck(int tets) const;
  /// RMS and largest per-step rotation change over the settled half of the hold (negative:
  /// no sample).
  double flutter_rms_rad() const;
  double flutter_max_rad() const { return samples_ > 0 ? flutter_max_ : -1; }
  /// (E + D - W) above its value at the hold's start, over the hold's largest energy (negative:
  /// no energy to compare with).
  double energy_error() const { return energy_peak_ > 0 ? energy_excess_ / energy_peak_ : -1; }
  /// Median |J - J^T| / |J| over the elements at the hold's end (negative: not reached).
  double asymmetry_median() const { return asymmetry_median_; }
  const std::vector<double>& rms_series() const { return rms_series_; }
  const std::vector<double>& max_series() const { return max_series_; }
  const std::vector<double>& kinetic_series() const { return kinetic_series_; }
  const std::vector<int>& inverted_series() const { return inverted_series_; }
  /// Per vertex, the largest rotation change of its elements in the settled window.
  const std::vector<double>& vertex_change() const { return vertex_change_; }

 private:
  void measure_energy(const StepState& step, const FeProblem& problem, double kinetic);
  void measure_asymmetry(const StepState& step, const FeProblem& problem);

  const FlutterThresholds thresholds_;
  RotationMethod method_;
  int ramp_steps_, hold_steps_, settle_from_;  ///< settle_from_: the settled half of the hold
  double dt_, alpha_, beta_;
  std::filesystem::path vtu_dir_;
  double blowup_ = 0;  ///< FlutterThresholds::blowup_displacement of the body
  int last_step_ = 0;
  std::vector<Mat3> previous_;
  std::vector<double> rms_series_, max_series_, kinetic_series_, vertex_change_;
  std::vector<int> inverted_series_;
  double flutter_rms_sum_ = 0, flutter_max_ = 0;
  long long samples_ = 0;
  // Energy balance over the hold (loads constant, supports still): E + D - W stays at its value
  // at the hold's start unless energy is created (a non-conservative force, an unstable
  // integrator) or removed (backward Euler's numerical dissipation).
  double hold_energy_ = 0, dissipated_ = 0, energy_excess_ = 0, energy_peak_ = 0;
  Eigen::VectorXd hold_displacement_;
  double asymmetry_median_ = -1;
  // Rotations of the state itself (the linearly implicit step's are the step start's), for the
  // energy and the asymmetry.
  std::unique_ptr<RotationExtractor> state_rotation_;
  std::vector<Mat3> state_rotations_;
};

}  // namespace corofem
