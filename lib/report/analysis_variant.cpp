#include "report/analysis_variant.hpp"

#include "scene/scene.hpp"

namespace corofem {

nlohmann::json to_json(const AnalysisVariant& v) {
  nlohmann::json j = nlohmann::json::object();
  if (v.solver) j["solver"] = v.solver->name();
  if (v.rotation) j["rotation"] = v.rotation->name();
  if (v.formulation) j["formulation"] = kFormulations.name(*v.formulation);
  if (v.galerkin) j["galerkin"] = kGalerkinMethods.name(*v.galerkin);
  if (v.hierarchy) j["hierarchy"] = kHierarchyKinds.name(*v.hierarchy);
  if (v.tolerance) j["tolerance"] = *v.tolerance;
  if (v.levels) j["levels"] = *v.levels;
  if (v.vcycles) j["vcycles"] = *v.vcycles;
  if (v.smoothing) j["smoothing"] = *v.smoothing;
  if (v.setup_reuse) j["setup_reuse"] = *v.setup_reuse;
  if (v.coarsening) j["coarsening"] = *v.coarsening;
  if (v.galerkin_refresh) j["galerkin_refresh"] = *v.galerkin_refresh;
  return j;
}

std::string label_of(const AnalysisVariant& variant) {
  std::string label;
  const nlohmann::json set = to_json(variant);  // held: items() refers into it
  for (auto& [key, value] : set.items())
    label += (label.empty() ? "" : " ") + key + "=" +
             (value.is_string() ? value.get<std::string>() : value.dump());
  return label;
}

nlohmann::json with_analysis(nlohmann::json scene, const AnalysisVariant& variant) {
  const nlohmann::json set = to_json(variant);  // held: items() refers into it
  for (auto& [key, value] : set.items()) scene["analysis"][key] = value;
  if (variant.solver) drop_unused_multigrid_keys(scene["analysis"]);
  return scene;
}

}  // namespace corofem
