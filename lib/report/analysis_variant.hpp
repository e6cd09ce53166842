#pragma once
// The report's variants of a scene: typed changes to its `analysis` (each set field replaces the
// scene's setting), written into the scene JSON with the settings' own name tables, so every
// variant a record holds is a scene `corofem run` re-runs, and no setting is spelled here.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "multigrid/multigrid_solver.hpp"
#include "rotation/rotation_method.hpp"
#include "scene/analysis_settings.hpp"

namespace corofem {

/// Every field initialized, so that a designated initializer naming a few says nothing of the
/// rest (-Wmissing-field-initializers).
struct AnalysisVariant {
  std::optional<SolverKind> solver{};
  std::optional<RotationMethod> rotation{};
  std::optional<Formulation> formulation{};
  std::optional<GalerkinMethod> galerkin{};
  std::optional<HierarchyKind> hierarchy{};
  std::optional<double> tolerance{};
  std::optional<int> levels{}, vcycles{}, smoothing{};
  std::optional<bool> setup_reuse{};
  std::optional<double> coarsening{};
  std::optional<double> galerkin_refresh{};  ///< MultigridParams::galerkin_refresh_change
};

/// The set fields as analysis keys and values (names from the name tables).
nlohmann::json to_json(const AnalysisVariant& variant);
/// "key=value" for each set field, in key order: a point's label in the speed-accuracy sweeps.
std::string label_of(const AnalysisVariant& variant);
/// `scene` with the variant's changes; a change to a solver that is not multigrid drops the
/// multigrid keys, which that solver would warn about.
nlohmann::json with_analysis(nlohmann::json scene, const AnalysisVariant& variant);

}  // namespace corofem
