#include "io/solver_record.hpp"

#include <cmath>
#include <vector>

namespace corofem {

nlohmann::json to_json(const HierarchyParams& p) {
  nlohmann::json j = {{"kind", kHierarchyKinds.name(p.kind)}, {"levels", p.levels}};
  j["first_cell_factor"] = p.first_cell_factor;  // meshes: of a lattice level that replaces one
  if (p.kind == HierarchyKind::Meshes) {
    j["min_coarsening"] = p.min_coarsening;
    j["end_below_vertices"] = p.end_below_vertices;
    j["coarsening"] = p.coarsening;
  }
  if (p.coarsest_vertices == kCoarsestSizedByFine)
    j["coarsest_vertices_rule"] = "sqrt(40 x fine vertices)";  // sized by the scene
  else if (p.coarsest_vertices > 0)
    j["coarsest_vertices"] = p.coarsest_vertices;
  if (p.coarsest_max_vertices > 0) j["coarsest_max_vertices"] = p.coarsest_max_vertices;
  return j;
}

namespace {

/// Parts by name, those that ran (a part that never ran, 0, is left out).
template <class Parts>
nlohmann::json parts_json(const Parts& parts) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, ms] : parts)
    if (ms != 0) j[name] = ms;
  return j;
}
nlohmann::json parts_json(std::initializer_list<std::pair<const char*, double>> parts) {
  return parts_json<std::initializer_list<std::pair<const char*, double>>>(parts);
}

/// The smoother as it describes itself, with the smoothings per cycle.
nlohmann::json smoother_json(const MultigridParams& p) {
  nlohmann::json j = to_json(make_smoother(p.smoother, p.smoother_parameters)->describe());
  j["pre_smoothing"] = p.pre_smoothing;
  j["post_smoothing"] = p.post_smoothing;
  return j;
}

}  // namespace

nlohmann::json to_json(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const Parameters& parameters) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : parameters.values())
    std::visit([&, &key = key](const auto& v) { j[key] = v; }, value);
  return j;
}

nlohmann::json to_json(const MultigridSetupParts& p) {
  nlohmann::json j =
      parts_json({{"transfers", p.transfers}, {"galerkin_streams", p.galerkin_streams}});
  if (p.coarse_meshes) j["coarse_meshes"] = *p.coarse_meshes;
  return j;
}

nlohmann::json to_json(const MultigridUpdateParts& p) {
  return parts_json(named_parts(p));
}

nlohmann::json to_json(const MultigridSolveParts& p) {
  return parts_json({{"fine_smooth", p.fine_smooth},
                     {"fine_residual", p.fine_residual},
                     {"fine_transfer", p.fine_transfer},
                     {"coarse_levels", p.coarse_levels},
                     {"coarsest", p.coarsest}});
}

nlohmann::json to_json(const MultigridParams& p) {
  return {{"hierarchy", to_json(p.hierarchy)},
          {"transfer", "barycentric in the containing or nearest coarse tet"},
          {"galerkin", kGalerkinMethods.name(p.galerkin)},
          {"smoother", smoother_json(p)},
          {"cycle",
           {{"kind", kCycleShapes.name(p.cycle)},
            {"vcycles", p.vcycles},
            {"max_iterations", p.max_iterations},
            {"tolerance", p.tolerance},
            {"coarsest", "cholmod"},
            {"coarsest_factorization", p.overlap_factorization
                                           ? "beside the first descent at 2+ threads and 3+ levels"
                                           : "in the update"},
            {"coarsest_refactor_change", p.coarsest_refactor_change}}},
          {"galerkin_refresh_change", p.galerkin_refresh_change}};
}

nlohmann::json to_json(const CoarseLevelOrigin& o) {
  switch (o.kind) {
    case CoarseLevelOrigin::Kind::Mesh:
      return {{"source", o.mesh},
              {"mesh_vertices", o.mesh_vertices},
              {"mesh_tets", o.mesh_tets},
              {"outside_points", o.fit.outside},
              {"far_outside_points", o.fit.far_outside},
              {"located_points", o.fit.located},
              {"max_outside_distance_edges", o.fit.max_outside_distance},
              {"max_abs_weight", o.fit.max_abs_weight},
              {"dropped_vertices", o.fit.dropped_vertices}};
    case CoarseLevelOrigin::Kind::Lattice:
      return {{"source", "lattice"}, {"cell", o.cell}};
    case CoarseLevelOrigin::Kind::LatticeBelowCoarsest:
      return {{"source", "lattice below the coarsest"}, {"cell", o.cell}};
    case CoarseLevelOrigin::Kind::LatticeForMesh:
      return {{"source", "lattice"}, {"cell", o.cell}, {"instead_of_mesh", o.fallback}};
  }
  return nullptr;
}

nlohmann::json to_json(const MultigridSummary& s) {
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t h = 0; h < s.levels.size(); ++h) {
    nlohmann::json level = {
        {"level", h}, {"vertices", s.levels[h].vertices}, {"blocks", s.levels[h].blocks}};
    if (h > 0 && h - 1 < s.origins.size()) level["built_from"] = to_json(s.origins[h - 1]);
    levels.push_back(level);
  }
  nlohmann::json out = {{"params", to_json(s.params)},
                        {"hierarchy", kHierarchyKinds.name(s.params.hierarchy.kind)},
                        {"levels", levels},
                        {"operator_complexity", s.operator_complexity},
                        {"setup_ms", to_json(s.setup)},
                        {"update_parts_ms", to_json(s.update)},
                        {"solve_parts_ms", to_json(s.solve)},
                        {"solves", s.solves},
                        {"rho", to_json(s.rho)},
                        {"iterations", to_json(s.iterations)},
                        {"coarsest_shifts", s.coarsest_shifts},
                        {"updates", s.updates},
                        {"coarsest_factorizations", s.coarsest_factorizations},
                        {"galerkin_refreshes", s.galerkin_refreshes},
                        {"deferred_updates", s.deferred_updates}};
  if (!s.ended_early.empty()) out["ended_early"] = s.ended_early;
  return out;
}

nlohmann::json to_json(const SolverChoice& choice) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const SolverTrial& t : choice.candidates) {
    nlohmann::json c = {{"name", t.name}, {"trial_ms", t.ms}, {"iterations", t.iterations}};
    const double cost = trial_cost(t, choice.warmup_solves);
    c["cost_ms"] = std::isfinite(cost) ? nlohmann::json(cost) : nlohmann::json(nullptr);
    if (!t.failure.empty()) c["failure"] = t.failure;
    candidates.push_back(std::move(c));
  }
  return {
      {"candidates", std::move(candidates)},
      {"trial_solves", choice.trial_solves},
      {"warmup_solves", choice.warmup_solves},
      {"decided_after", choice.decided_after},
      {"rule", choice.rule},
      {"chosen", choice.chosen.empty() ? nlohmann::json(nullptr) : nlohmann::json(choice.chosen)}};
}

}  // namespace corofem
