#pragma once
// `corofem tune`: the cheapest settings of a scene whose answer stays within a target error of
// the finest affordable one. The reference: the finest resolution (a finer mesh than the scene's
// where it can be re-meshed), CHOLMOD (static Newton: its sparse LU at a tight tolerance), the
// exact rotation minimizer, the scene's time step; its own discretization error estimated by
// Richardson extrapolation over two or three resolutions. The search: every axis screened alone
// from the reference (each ordered family stopped at its first miss), then the combinations of
// the values that met the target, cheapest predicted first (errors add, costs multiply), a few
// measured; never the full grid. The answer is re-measured in a separate run of the scene JSON
// it writes.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "tune/tune_axes.hpp"
#include "tune/tune_quantity.hpp"

namespace corofem {

struct TuneOptions {
  double target = 1e-2;   ///< relative error of the quantity, reference's own error included
  QuantitySpec quantity;  ///< the tip is found on the reference
  TuneAxesOptions axes;
  double budget_minutes = 5;  ///< screening and combinations stop when it is spent
  int combinations = 4;       ///< combinations measured, cheapest predicted first
  std::ostream* progress = nullptr;
};

struct TuneOutcome {
  nlohmann::json record;       ///< tune.json (README "corofem tune")
  nlohmann::json tuned_scene;  ///< the answer (or the closest setting), without output keys
  int exit_status = 1;         ///< 0: target met in the re-run; 1: not met or refused
};

/// Tunes the scene `raw` (relative paths against `base_dir`, `name` in messages). Throws
/// InputError for a bad scene or options.
TuneOutcome tune_scene(const nlohmann::json& raw, const std::filesystem::path& base_dir,
                       const std::string& name, const TuneOptions& options);

}  // namespace corofem
