#pragma once
// One rank's part of a mesh distributed over MPI ranks: the rank owns a contiguous range
// of the (locality-ordered) vertices, [begin, end), the block rows it gives PETSc; it holds the
// tets that touch an owned vertex (every element contributing to its rows, so its rows assemble
// complete with no matrix entries sent between ranks) and the vertices those tets reach beyond
// its range (the halo, whose values it receives after each solve). A tet on a part boundary is
// held, and its element work done, by every rank it touches; it is owned by the rank of its
// smallest vertex, so counts over owned tets sum to the mesh's.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

/// The first of `count` vertices rank `rank` of `ranks` owns: equal contiguous shares (rank =
/// ranks gives count).
int rank_share_start(int count, int rank, int ranks);

struct RankPart {
  /// Local numbering: the owned vertices first, in global order, then the halo, ascending; the
  /// held tets in global order. Tags are the whole mesh's.
  TetMesh mesh;
  std::vector<int> global_vertex;  ///< local vertex -> global vertex
  std::vector<int> global_tet;     ///< local tet -> global tet
  std::vector<char> owned_tet;     ///< per local tet: its smallest global vertex is owned
  int owned_vertices = 0, halo_vertices = 0;
  int first_vertex = 0;  ///< the global index of local vertex 0
  int global_vertices = 0, global_tets = 0;

  int owned_tets() const;
};

/// Renumbers the vertices of `mesh` so that each part of `part_of_vertex` (parts 0..parts-1) is a
/// contiguous range, in the order it had within the part (keeping its locality); the tets keep
/// their order. Returns each part's first vertex (parts + 1 entries) and, in `new_index`, every
/// old vertex's new number.
std::vector<int> group_vertices_by_part(TetMesh& mesh, const std::vector<int>& part_of_vertex,
                                        int parts, std::vector<int>& new_index);

/// The part owning the vertices [begin, end) of `whole`; `extra_rings` as rank_part's.
RankPart rank_part_of_range(const TetMesh& whole, int begin, int end, int extra_rings = 0);

/// Every part of `whole` in turn, for the one rank that holds the whole mesh: part r owns the
/// vertices [first[r], first[r + 1]). Without extra rings, the tets of all parts are listed in
/// one pass over the mesh at construction (each tet under the parts of its vertices), so cutting
/// every part costs about one pass, not one per part; with rings, each cut scans the mesh
/// (rank_part_of_range). cut(r) equals rank_part_of_range(whole, first[r], first[r + 1],
/// extra_rings).
class RankPartCutter {
 public:
  RankPartCutter(const TetMesh& whole, std::vector<int> first, int extra_rings = 0);
  RankPart cut(int rank);

 private:
  const TetMesh& whole_;
  std::vector<int> first_;
  int extra_rings_;
  std::vector<int> held_start_, held_;  ///< no rings: part r's tets, ascending
  std::vector<int> local_;  ///< per vertex of `whole`: -1 between cuts (part_holding's scratch)
};

/// Rank `rank` of `ranks`'s part of `whole` (its vertices split by rank_share_start). With
/// `extra_rings` > 0 the part holds that many more rings of tets (those sharing a vertex with a
/// held one) beyond the ones touching its vertices: what a rotation smoothed over neighbouring
/// tets, one ring per pass, needs to give the tets touching its vertices the same rotation as
/// on the whole mesh.
RankPart rank_part(const TetMesh& whole, int rank, int ranks, int extra_rings = 0);

}  // namespace corofem
