#pragma once
// One scene, start to finish: build, solve (static or dynamic), and the result record.
#include <nlohmann/json.hpp>

#include "fem/simulation_result.hpp"
#include "scene/scene.hpp"

namespace corofem {

struct SceneRun {
  nlohmann::json record;  ///< the RESULT.json of `corofem run`
  bool converged = false;
};

/// Runs the scene; progress lines go to `progress` if given. Writes the scene's VTU if it asks.
/// Throws InputError for bad input, NumericalFault for NaN/inf; non-convergence is recorded.
SceneRun run_scene(const Scene& scene, std::ostream* progress = nullptr);

}  // namespace corofem
