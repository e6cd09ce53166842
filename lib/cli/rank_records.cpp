#include "cli/rank_records.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "core/memory_usage.hpp"
#include "io/vtu_writer.hpp"
#include "rotation/quaternion.hpp"
#include "solver/mpi_launch.hpp"

namespace corofem {

namespace {

/// The phases a distributed run's table gives per rank.
const std::vector<std::string> kRankPhases = {"rotate", "assemble", "forces", "system",
                                              "update", "solve",    "checks", "total"};

}  // namespace

nlohmann::json rank_table(SceneSimulation& simulation, const SimulationResult& result) {
  const RankPart& part = *simulation.part();
  std::vector<std::string> keys = {"owned_tets",    "held_tets",   "owned_vertices",
                                   "halo_vertices", "peak_rss_kb", "built_whole_body"};
  std::vector<double> mine = {static_cast<double>(part.owned_tets()),
                              static_cast<double>(simulation.problem().mesh.num_tets()),
                              static_cast<double>(part.owned_vertices),
                              static_cast<double>(part.halo_vertices),
                              static_cast<double>(peak_rss_kb()),
                              simulation.built_whole_body() ? 1.0 : 0.0};
  for (const std::string& phase : kRankPhases) {
    keys.push_back(phase + "_ms");
    const auto it = result.timings_ms.find(phase);
    mine.push_back(it == result.timings_ms.end() ? 0.0 : it->second);
  }
  const std::vector<double> all = gather_on_rank0(mine);
  if (all.empty()) return nullptr;
  const std::size_t fields = keys.size(), ranks = all.size() / fields;
  nlohmann::json per_rank = nlohmann::json::array(), max, min;
  for (std::size_t r = 0; r < ranks; ++r) {
    nlohmann::json row = {{"rank", r}};
    for (std::size_t k = 0; k < fields; ++k) row[keys[k]] = all[r * fields + k];
    per_rank.push_back(std::move(row));
  }
  for (std::size_t k = 0; k < fields; ++k) {
    double hi = all[k], lo = all[k];
    for (std::size_t r = 1; r < ranks; ++r) {
      hi = std::max(hi, all[r * fields + k]);
      lo = std::min(lo, all[r * fields + k]);
    }
    max[keys[k]] = hi;
    min[keys[k]] = lo;
  }
  return {{"per_rank", std::move(per_rank)}, {"max", std::move(max)}, {"min", std::move(min)}};
}

void add_gathered_fields(SceneSimulation& simulation, const SimulationResult& result,
                         nlohmann::json& r) {
  const RankPart& part = *simulation.part();
  const TetMesh& mesh = simulation.problem().mesh;
  if (part.global_vertices > kMaxGatheredVertices) {  // the same decision on every rank
    r["fields"] = "not gathered: " + std::to_string(part.global_vertices) + " vertices, above " +
                  std::to_string(kMaxGatheredVertices) + " (output.vtu writes them piece by piece)";
    return;
  }
  std::vector<double> mine;  // per owned vertex: its number in the scene, tag, rest, displacement
  for (int v = 0; v < part.owned_vertices; ++v) {
    mine.push_back(static_cast<double>(simulation.scene_vertex_index()[v]));
    mine.push_back(static_cast<double>(mesh.node_tags[v]));
    for (int c = 0; c < 3; ++c) mine.push_back(mesh.rest[v][c]);
    for (int c = 0; c < 3; ++c) mine.push_back(result.displacement[3 * v + c]);
  }
  const std::vector<double> all = gather_on_rank0(mine);
  std::vector<double> rotations_mine;  // per owned tet: tag, quaternion, reflected
  if (simulation.scene().output.rotations) {
    std::vector<Mat3> final_rotations = result.rotations;  // of the final displacement
    simulation.extractor().extract(simulation.problem().positions(result.displacement),
                                   final_rotations);
    for (int e = 0; e < mesh.num_tets(); ++e) {
      if (!part.owned_tet[e]) continue;
      const auto q = to_quaternion(final_rotations[e]);
      rotations_mine.insert(rotations_mine.end(),
                            {static_cast<double>(mesh.element_tags[e]), q.w(), q.x(), q.y(), q.z(),
                             final_rotations[e].determinant() < 0 ? 1.0 : 0.0});
    }
  }
  const std::vector<double> rotations_all = gather_on_rank0(rotations_mine);
  if (all.empty()) return;  // not rank 0
  const std::size_t vertices = all.size() / 8;
  nlohmann::json tags(vertices, 0), rest(vertices, nullptr), disp(vertices, nullptr);
  for (std::size_t i = 0; i + 8 <= all.size(); i += 8) {
    const auto v = static_cast<std::size_t>(all[i]);
    tags[v] = static_cast<std::size_t>(all[i + 1]);
    rest[v] = {all[i + 2], all[i + 3], all[i + 4]};
    disp[v] = {all[i + 5], all[i + 6], all[i + 7]};
  }
  r["node_tags"] = std::move(tags);
  r["rest"] = std::move(rest);
  r["displacement"] = std::move(disp);
  if (!simulation.scene().output.rotations) return;
  nlohmann::json element_tags = nlohmann::json::array(), quats = nlohmann::json::array(),
                 reflected = nlohmann::json::array();
  for (std::size_t i = 0; i + 6 <= rotations_all.size(); i += 6) {
    const auto tag = static_cast<std::size_t>(rotations_all[i]);
    element_tags.push_back(tag);
    quats.push_back(
        {rotations_all[i + 1], rotations_all[i + 2], rotations_all[i + 3], rotations_all[i + 4]});
    if (rotations_all[i + 5] != 0) reflected.push_back(tag);
  }
  r["element_tags"] = std::move(element_tags);
  r["rotations"] = std::move(quats);
  r["reflected_elements"] = std::move(reflected);
}

std::filesystem::path write_rank_pieces(SceneSimulation& simulation, const SimulationResult& result,
                                        const std::filesystem::path& file) {
  const MpiLaunch mpi = mpi_launch();
  std::filesystem::path pvtu = file;
  pvtu.replace_extension(".pvtu");
  const auto piece_name = [&](int rank) {
    return pvtu.stem().string() + "_r" + std::to_string(rank) + ".vtu";
  };
  const RankPart& part = *simulation.part();
  const TetMesh& held = simulation.problem().mesh;
  TetMesh owned;  // the part's vertices, its owned tets
  owned.rest = held.rest;
  std::vector<Mat3> rotations;
  for (int e = 0; e < held.num_tets(); ++e)
    if (part.owned_tet[e]) {
      owned.tets.push_back(held.tets[e]);
      rotations.push_back(result.rotations[e]);
    }
  write_vtu(pvtu.parent_path() / piece_name(mpi.rank), owned, result.displacement, rotations);
  if (mpi.rank == 0) {
    std::vector<std::string> pieces;
    for (int r = 0; r < mpi.size; ++r) pieces.push_back(piece_name(r));
    write_pvtu(pvtu, pieces);
  }
  return pvtu;
}

}  // namespace corofem
