#pragma once
// What a run on a distributed mesh records without gathering the mesh to one rank:
// per rank its sizes, peak RSS and phase times, with the max and min over the ranks; the fields
// (rest positions, displacements, rotations) gathered on rank 0; a parallel VTU written piece
// by piece, one per rank.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "fem/simulation_result.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {

/// The record's `ranks` entry on rank 0 (null elsewhere): per rank owned and held tets, owned and
/// halo vertices, peak RSS and each phase's milliseconds, and `max` and `min` of each over ranks.
nlohmann::json rank_table(SceneSimulation& simulation, const SimulationResult& result);

/// Above this many vertices the fields are not gathered on rank 0 (some 1 GB of JSON text).
inline constexpr int kMaxGatheredVertices = 2'000'000;

/// The whole body's node_tags, rest and displacement on rank 0, in the scene's vertex order (as a
/// run on one rank records them), up to kMaxGatheredVertices (else `fields` says why they are
/// absent); with output.rotations the rotations
/// of the final displacement of every rank's owned tets, with their element_tags.
void add_gathered_fields(SceneSimulation& simulation, const SimulationResult& result,
                         nlohmann::json& record);

/// `file` (.pvtu, on rank 0) and this rank's piece beside it, FILE_STEM_rR.vtu: the part's
/// vertices and its owned tets. Returns the .pvtu's path.
std::filesystem::path write_rank_pieces(SceneSimulation& simulation, const SimulationResult& result,
                                        const std::filesystem::path& file);

}  // namespace corofem
