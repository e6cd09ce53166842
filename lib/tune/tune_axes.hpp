#pragma once
// The settings `corofem tune` searches over, as axes of values: the mesh's resolution, the
// rotation method, the solver with its tolerance, hierarchy and cycle (or static Newton's
// tolerance, its tangent factored or on the multigrid, and load increments), and the time step.
// Each value is a change to the scene JSON, so every candidate, and the answer, is a scene `corofem
// run` runs as it is.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace corofem {

/// One value of an axis.
struct AxisValue {
  std::string label{};
  /// RFC 7396 merge patch on the scene ({"analysis": {...}} or {"mesh": {...}}; null deletes).
  nlohmann::json patch = nlohmann::json::object();
  int time_factor = 1;  ///< dt axis: the scene run at dt x this (same end time)
  /// Values of one family are ordered most accurate first: the search stops a family at the
  /// first value that misses the target (a looser one would miss it too).
  std::string family{};
};

struct TuneAxis {
  std::string name;  ///< resolution | rotation | solver | load_steps | time_step
  std::vector<AxisValue> values{};
  int reference = 0;  ///< the most accurate value: the reference setting's
  int given = 0;      ///< the scene's own value (when the scene is one of the values)
};

struct TuneAxesOptions {
  bool resolution_free = true;  ///< false: the scene's mesh only
  /// The reference may be a finer mesh than the scene's up to this many tets.
  double finest_tets = 300000;
};

/// The axes for `scene` (parsed from `raw`), with `note` saying what the resolution axis could
/// not do (a mesh file cannot be re-meshed; a surface is not refined past its triangles).
std::vector<TuneAxis> tune_axes(const Scene& scene, const nlohmann::json& raw,
                                const TuneAxesOptions& options, std::string& note);

/// The product of the setting's time factors: its dt over the scene's.
int time_factor(const std::vector<TuneAxis>& axes, const std::vector<int>& setting);

/// `raw` with value setting[i] of axis i applied (merge patches, then the time step; the
/// multigrid keys dropped for a solver that is not multigrid; output dropped). Nullopt where the
/// time step cannot be scaled (its step counts are not multiples of the factor).
std::optional<nlohmann::json> apply_setting(const nlohmann::json& raw,
                                            const std::vector<TuneAxis>& axes,
                                            const std::vector<int>& setting);

}  // namespace corofem
