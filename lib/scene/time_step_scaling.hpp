#pragma once
// A dynamic scene run for the same physical time at another time step: the stability study's
// refined steps and `corofem tune`'s coarser ones.
#include <nlohmann/json.hpp>
#include <optional>

namespace corofem {

/// `scene` at dt x numerator / denominator: analysis.steps and the loads' ramp_steps and
/// release_step x denominator / numerator. Nullopt where a count is not a whole multiple.
std::optional<nlohmann::json> time_step_scaled(const nlohmann::json& scene, int numerator,
                                               int denominator);

}  // namespace corofem
