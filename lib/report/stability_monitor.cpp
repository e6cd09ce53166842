#include "report/stability_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/errors.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/corotated_system.hpp"
#include "fem/rotation_tangent.hpp"
#include "io/vtu_writer.hpp"
#include "rotation/quaternion.hpp"

namespace corofem {
namespace {

/// Thrown by the monitor when the displacement leaves any physical range.
struct BlowUp : NumericalFault {
  using NumericalFault::NumericalFault;
};

}  // namespace

StabilityMonitor::StabilityMonitor(RotationMethod method, int ramp_steps, int hold_steps, double dt,
                                   double alpha, double beta, std::filesystem::path vtu_dir)
    : method_(method),
      ramp_steps_(ramp_steps),
      hold_steps_(hold_steps),
      settle_from_(ramp_steps + hold_steps / 2),
      dt_(dt),
      alpha_(alpha),
      beta_(beta),
      vtu_dir_(std::move(vtu_dir)) {}

void StabilityMonitor::observe(const StepState& st, const FeProblem& problem) {
  last_step_ = st.step;
  if (blowup_ == 0) {
    blowup_ = thresholds_.blowup_displacement(problem.mesh.rest);
    vertex_change_.assign(problem.mesh.rest.size(), 0.0);
  }
  const int tets = problem.mesh.num_tets();
  double sum2 = 0, largest = 0;
  if (!previous_.empty()) {
    for (int e = 0; e < tets; ++e) {
      const double d = angle_between(st.rotations[e], previous_[e]);
      sum2 += d * d;
      largest = std::max(largest, d);
      if (st.step > settle_from_)
        for (int v : problem.mesh.tets[e]) vertex_change_[v] = std::max(vertex_change_[v], d);
    }
  }
  previous_ = st.rotations;
  rms_series_.push_back(std::sqrt(sum2 / tets));
  max_series_.push_back(largest);
  if (st.step > settle_from_) {
    flutter_rms_sum_ += sum2;
    samples_ += tets;
    flutter_max_ = std::max(flutter_max_, largest);
  }
  const double kinetic = 0.5 * st.velocity.cwiseProduct(st.velocity).dot(problem.mass);
  kinetic_series_.push_back(kinetic);
  if (st.step >= ramp_steps_) measure_energy(st, problem, kinetic);
  if (st.step == ramp_steps_ + hold_steps_) measure_asymmetry(st, problem);
  inverted_series_.push_back(count_inverted(problem, problem.positions(st.displacement)));
  if (st.displacement.lpNorm<Eigen::Infinity>() > blowup_)
    throw BlowUp("displacement beyond " + std::to_string(thresholds_.blowup_factor) +
                 "x the body's diagonal at step " + std::to_string(st.step));
  if (!vtu_dir_.empty() && (st.step % 10 == 0)) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.vtu", st.step);
    std::filesystem::create_directories(vtu_dir_);
    write_vtu(vtu_dir_ / name, problem.mesh, st.displacement, st.rotations);
  }
}

void StabilityMonitor::measure_energy(const StepState& st, const FeProblem& problem,
                                      double kinetic) {
  if (!state_rotation_) {
    state_rotation_ = make_rotation_extractor(method_, problem.mesh);
    state_rotations_ = st.rotations;
  }
  state_rotation_->extract(problem.positions(st.displacement), state_rotations_);
  const double energy =
      kinetic + elastic_energy(problem.elements, problem.mesh, state_rotations_, st.displacement);
  if (st.step == ramp_steps_) {
    hold_energy_ = energy;
    hold_displacement_ = st.displacement;
  } else {
    Eigen::VectorXd kv;
    problem.stiffness.multiply(st.velocity, kv);
    dissipated_ += dt_ * (alpha_ * st.velocity.dot(problem.mass.cwiseProduct(st.velocity)) +
                          beta_ * st.velocity.dot(kv));
  }
  const double work = problem.external_force.dot(st.displacement - hold_displacement_);
  energy_excess_ = std::max(energy_excess_, energy + dissipated_ - work - hold_energy_);
  energy_peak_ = std::max({energy_peak_, energy, std::abs(work)});
}

void StabilityMonitor::measure_asymmetry(const StepState& st, const FeProblem& problem) {
  // Conservativeness of the method on this state: |J - J^T| / |J| per element, its median.
  const RotationTangent tangent(problem, method_);
  const auto positions = problem.positions(st.displacement);
  std::vector<double> asymmetries(problem.mesh.tets.size());
  for (int e = 0; e < problem.mesh.num_tets(); ++e)
    asymmetries[e] = asymmetry(tangent.element_jacobian(e, positions, state_rotations_[e]));
  std::nth_element(asymmetries.begin(), asymmetries.begin() + asymmetries.size() / 2,
                   asymmetries.end());
  asymmetry_median_ = asymmetries[asymmetries.size() / 2];
}

bool StabilityMonitor::flutters() const {
  return flutter_max_ > thresholds_.max_rad ||
         (samples_ > 0 && std::sqrt(flutter_rms_sum_ / samples_) > thresholds_.rms_rad);
}

bool StabilityMonitor::stuck(int tets) const {
  return !inverted_series_.empty() &&
         inverted_series_.back() > thresholds_.stuck_inverted_share * tets;
}

double StabilityMonitor::flutter_rms_rad() const {
  return samples_ > 0 ? std::sqrt(flutter_rms_sum_ / samples_) : -1;
}

}  // namespace corofem
