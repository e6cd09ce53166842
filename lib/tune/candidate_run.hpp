#pragma once
// One run of a candidate setting for `corofem tune`: its final state and what it cost.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tune/tune_quantity.hpp"

namespace corofem {

struct CandidateRun {
  bool completed = false;
  std::string failure;  ///< why not: the error's message, "did not converge: ...", "unstable ..."
  FinalState state;
  int tets = 0;
  /// Dynamic: the median step after warm-up; static: the whole solve, meshing and setup included.
  double ms_per_step = 0;
  /// What the search minimizes: dynamic, ms per step of the scene's own dt (ms_per_step divided
  /// by the time factor); static, ms_per_step.
  double cost_ms = 0;
  double linear_iterations_per_step = 0;
};

/// Runs `scene` (relative paths against `base_dir`), whose time step is `time_factor` x the
/// scene's own. A dynamic run whose displacement leaves 100x the body's diagonal (the stability
/// study's blow-up threshold) is stopped as unstable. Never throws for a failing run.
CandidateRun run_candidate(const nlohmann::json& scene, const std::filesystem::path& base_dir,
                           const std::string& name, int time_factor);

}  // namespace corofem
