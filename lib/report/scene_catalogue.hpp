#pragma once
// The report's scenes as scene JSON (README "Scene format"), so every record can be re-run with
// `corofem run`. Procedural scenes need no data: a cantilever bar, a twisting bar and a quadruped
// (mesh/quadruped_mesh.hpp). With a models folder, the paper's bunny, horse and dragon.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace corofem {

/// Mesh resolution: `small` for tests, quick runs and the stability study; S, M, L are the paper's
/// three sizes (about 11k, 34k and 67k tets; the paper's bunny, horse and dragon rows); XL, about
/// 270k, only for the multigrid's size independence.
enum class SceneSize { Small, S, M, L, XL };
std::string size_name(SceneSize size);       ///< "small", "11k", "34k", "67k", "270k"
std::string paper_model_of(SceneSize size);  ///< the paper row of that size: bunny, horse, dragon
int paper_levels(SceneSize size);            ///< the paper's level count: 3, 4, 4 (2 for small)

/// "quadruped", "cantilever", "twisting-bar" (the table's order).
std::vector<std::string> procedural_models();
/// "bunny", "horse", "dragon": the surfaces of the models folder.
std::vector<std::string> file_models();
/// The size of a file model in the paper (bunny S, horse M, dragon L).
SceneSize file_model_size(const std::string& model);

/// A dynamic corotated scene of `model` at `size`, `steps` long, with the report's default
/// analysis (energy-newton, MG-PCG to `tolerance`, paper_levels(size) levels on re-meshed
/// hierarchies; the models: one level per surface of the folder, L0 to L2). The table runs:
/// bars fixed at x = 0 (sagging under gravity; twisted at the far end), the quadruped fixed at its
/// hind feet with its shoulders pulled up, the bunny and dragon fixed at their base and pulled, the
/// horse fixed at its hind hooves with its shoulders pulled up. Models read from `models_dir`.
nlohmann::json table_scene(const std::string& model, SceneSize size, int steps, double tolerance,
                           const std::filesystem::path& models_dir = {});

/// `scene` with every Young's modulus (the material's and its regions') times `scale`.
nlohmann::json with_young_scaled(nlohmann::json scene, double scale);

/// The region whose mean displacement the resolution sweep compares (a box [[lo],[hi]]).
nlohmann::json probe_box(const std::string& model);

/// Scenes built to break rotation extractors (issue: stability): "bar-twist" (past 360 degrees),
/// "bar-stretch" (to 3x), "block-squash" (until elements invert, then released),
/// "quadruped-stretched", "quadruped-stretched-far" (2.5x the pull), "quadruped-posed" (stiff legs,
/// soft knees, fore legs folded); with a
/// models folder also "horse-stretched" (a stress case: the hind legs pulled into strands),
/// "horse-stretched-paper" (a quarter of its pull: the paper's Figure 5 strength) and
/// "horse-posed" (the paper's pose). Load for `ramp_steps`, hold for
/// `hold_steps` (the squash is released at the start of the hold). Solver: CHOLMOD.
std::vector<std::string> stability_scene_ids(bool with_models);
/// Whether the study runs scene `id` only at full length (or where --only names it): true for
/// "quadruped-stretched", stable under every method and integrator, which decides no verdict
/// ("quadruped-stretched-far" is the same scene pulled 2.5x as hard): it would cost the main job
/// its time and tell nothing.
bool stability_scene_full_only(const std::string& id);
nlohmann::json stability_scene(const std::string& id, SceneSize size, int ramp_steps,
                               int hold_steps, const std::filesystem::path& models_dir = {});

/// Static scenes for the model's accuracy against CalculiX NLGEOM (report/model_accuracy.hpp):
/// "cantilever" (the table's bar under gravity, drooping far), "twisting-bar" (the bar twisted by
/// a torque on its free end: two opposite forces on its top and bottom edges) and "quadruped" (the
/// table's pull on the shoulders), all with integrator newton, 20 increments, tolerance 1e-10.
std::vector<std::string> model_accuracy_ids();
nlohmann::json model_accuracy_scene(const std::string& id, SceneSize size);

}  // namespace corofem
