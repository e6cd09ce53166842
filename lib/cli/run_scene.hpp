#pragma once
// One scene, start to finish: build, solve (static or dynamic), and the result record.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/section_counter.hpp"
#include "fem/simulation_result.hpp"
#include "scene/scene.hpp"

namespace corofem {

struct SceneRun {
  nlohmann::json record;  ///< the RESULT.json of `corofem run`
  bool converged = false;
};

/// What `corofem run --count-phases` counts with: the source, and for callgrind the output file
/// valgrind writes (empty: its default, callgrind.out.<pid>).
struct PhaseCounting {
  CountSource source = CountSource::Callgrind;
  std::string callgrind_file;
};

/// Runs the scene; progress lines go to `progress` if given. Writes the scene's VTU if it asks.
/// With `counting`, the record's `phase_counts` holds each phase's and solver part's counts from
/// the first step on (io/phase_counts_record.hpp), or says why they could not be counted.
/// Throws InputError for bad input, NumericalFault for NaN/inf; non-convergence is recorded.
SceneRun run_scene(const Scene& scene, std::ostream* progress = nullptr,
                   const std::optional<PhaseCounting>& counting = std::nullopt);

}  // namespace corofem
