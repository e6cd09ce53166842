#pragma once
// What a rank of a distributed run receives from rank 0, the one rank that builds the whole
// body: its part of the mesh (mesh/rank_part.hpp) with its tets' materials, its supports and
// its rows of the loads; each of its vertices' number in the scene's order; and, for petsc-mg, the
// hierarchy's transfers (the finest one's rows of its own vertices, the coarser ones whole: the
// coarse levels are small and replicated).
#include <vector>

#include "mesh/rank_part.hpp"
#include "multigrid/transfer.hpp"
#include "scene/scene_problem.hpp"

namespace corofem {

struct RankShare {
  RankPart part;                        ///< its mesh moved into `body`
  SceneBody body;                       ///< the part's body (body_part)
  std::vector<int> scene_vertex_index;  ///< per owned vertex: its number in the scene's order
  std::vector<Transfer> transfers;      ///< petsc-mg only, finest first
};

/// The share of `part`, cut from `whole` (mesh/rank_part.hpp), whose vertices the partition
/// numbered: the whole body's vertex g is the scene's vertex scene_vertex[g]. `transfers`: the
/// whole hierarchy's (or none).
RankShare make_rank_share(const SceneBody& whole, const std::vector<int>& scene_vertex,
                          RankPart part, const std::vector<Transfer>& transfers);

/// The share as bytes (core/byte_stream.hpp), and back.
std::vector<char> pack_rank_share(const RankShare& share);
RankShare unpack_rank_share(const std::vector<char>& bytes);

}  // namespace corofem
