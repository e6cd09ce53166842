// Rotation extraction per element on two consecutive frames of a real simulation (~67k tets):
// warm (started from the previous frame's rotations, as in a running simulation) and cold (from
// identity). Counters: ns per element, iterations per element (median, 99th percentile, share
// <= 2). Targets (issue 3): energy-newton warm <= 2 iterations on 99% and <= 300 ns/element;
// energy-exact <= 1.5x polar (the ratio is in BM_RotationRatio, taken in one run).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench_support.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem::bench {
namespace {

struct Prepared {
  FeProblem& problem;
  std::vector<Vec3> previous, current;
  std::vector<Mat3> warm;  ///< rotations of the previous frame by the method itself
};

Prepared prepare(const std::string& model, RotationExtractor& extractor) {
  FeProblem& p = paper_problem(model);
  const SimulatedFrames& frames = simulated_frames(model);
  Prepared prep{p, p.positions(frames.previous), p.positions(frames.current),
                std::vector<Mat3>(p.mesh.tets.size(), Mat3::Identity())};
  // Bring the method's own state to frame 7 by running it along the frames 6 -> 7 path once.
  extractor.extract(prep.previous, prep.warm);
  extractor.extract(prep.previous, prep.warm);
  return prep;
}

void add_iteration_counters(benchmark::State& state, const ExtractionStats& stats) {
  std::vector<int> it(stats.iterations.begin(), stats.iterations.end());
  if (it.empty()) return;
  std::sort(it.begin(), it.end());
  state.counters["iter_median"] = it[it.size() / 2];
  state.counters["iter_p99"] = it[static_cast<std::size_t>(0.99 * (it.size() - 1))];
  state.counters["iter_max"] = it.back();
  state.counters["share_le2_iter"] =
      static_cast<double>(std::upper_bound(it.begin(), it.end(), 2) - it.begin()) / it.size();
  state.counters["fallbacks"] = stats.fallbacks;
}

void BM_Rotation(benchmark::State& state, const std::string& method, bool warm) {
  const std::string model = "dragon";
  auto extractor =
      make_rotation_extractor(rotation_method_named(method), paper_problem(model).mesh);
  Prepared prep = prepare(model, *extractor);
  std::vector<Mat3> rotations;
  for (auto _ : state) {
    state.PauseTiming();
    rotations = warm ? prep.warm : std::vector<Mat3>(prep.warm.size(), Mat3::Identity());
    state.ResumeTiming();
    extractor->extract(prep.current, rotations);
    benchmark::DoNotOptimize(rotations.data());
  }
  const double elements = prep.problem.mesh.num_tets();
  state.counters["tets"] = elements;
  // Rate of (elements / 1e9) per second, inverted: nanoseconds per element.
  state.counters["ns_per_element"] = benchmark::Counter(
      elements * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  add_iteration_counters(state, extractor->stats());
  // How far the warm start is from the answer: angle between the two frames' rotations.
  std::vector<double> change;
  for (std::size_t e = 0; e < rotations.size(); ++e)
    change.push_back(angle_between(rotations[e], prep.warm[e]));
  std::sort(change.begin(), change.end());
  state.counters["frame_change_median_rad"] = change[change.size() / 2];
  state.counters["frame_change_p99_rad"] =
      change[static_cast<std::size_t>(0.99 * (change.size() - 1))];
}

/// energy-exact / polar and energy-newton(warm) / polar, timed alternately in the same run.
void BM_RotationRatio(benchmark::State& state) {
  const std::string model = "dragon";
  FeProblem& p = paper_problem(model);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  auto exact = make_rotation_extractor(RotationMethod::EnergyExact, p.mesh);
  auto newton = make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh);
  Prepared pp = prepare(model, *polar), pe = prepare(model, *exact), pn = prepare(model, *newton);
  using clock = std::chrono::steady_clock;
  double t_polar = 0, t_exact = 0, t_newton = 0;
  std::vector<Mat3> r;
  for (auto _ : state) {
    auto time = [&](RotationExtractor& x, const Prepared& prep) {
      r = prep.warm;
      const auto start = clock::now();
      x.extract(prep.current, r);
      return std::chrono::duration<double>(clock::now() - start).count();
    };
    t_polar += time(*polar, pp);
    t_exact += time(*exact, pe);
    t_newton += time(*newton, pn);
  }
  state.counters["exact_over_polar"] = t_exact / t_polar;
  state.counters["newton_over_polar"] = t_newton / t_polar;
}

#define ROTATION_CASES(name, method)                                      \
  BENCHMARK_CAPTURE(BM_Rotation, name##_warm, std::string(method), true)  \
      ->Unit(benchmark::kMillisecond);                                    \
  BENCHMARK_CAPTURE(BM_Rotation, name##_cold, std::string(method), false) \
      ->Unit(benchmark::kMillisecond)

ROTATION_CASES(energy_newton, "energy-newton");
ROTATION_CASES(energy_exact, "energy-exact");
ROTATION_CASES(polar, "polar");
ROTATION_CASES(polar_fixed, "polar-fixed");
ROTATION_CASES(polar_smoothed, "polar-smoothed");
ROTATION_CASES(qr, "qr");
ROTATION_CASES(mueller2016, "mueller2016");
BENCHMARK(BM_RotationRatio)->Unit(benchmark::kMillisecond)->Iterations(20);

}  // namespace
}  // namespace corofem::bench
