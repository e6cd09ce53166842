// A rank's part of a distributed mesh (issue 37): what it owns, what it holds, and that the parts
// together are the mesh, checked against brute-force definitions on a box mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "mesh/box_mesh.hpp"
#include "mesh/rank_part.hpp"

namespace corofem {
namespace {

/// Tets sharing a vertex with one of `tets` (the ring around them, `tets` included).
std::set<int> ring_around(const TetMesh& mesh, const std::set<int>& tets) {
  std::set<int> vertices, ring;
  for (int t : tets) vertices.insert(mesh.tets[t].begin(), mesh.tets[t].end());
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int v : mesh.tets[t])
      if (vertices.count(v)) ring.insert(t);
  return ring;
}

TEST(RankPart, PartsOwnEveryVertexAndTetOnceAndHoldWhatTheirRowsNeed) {
  const TetMesh whole = make_box_mesh({3, 1, 1}, {9, 3, 3});
  for (int ranks : {1, 2, 3, 5}) {
    SCOPED_TRACE(ranks);
    int owned_vertices = 0, owned_tets = 0;
    for (int rank = 0; rank < ranks; ++rank) {
      const RankPart part = rank_part(whole, rank, ranks);
      const int begin = rank_share_start(whole.num_vertices(), rank, ranks);
      const int end = rank_share_start(whole.num_vertices(), rank + 1, ranks);
      EXPECT_EQ(part.first_vertex, begin);
      EXPECT_EQ(part.owned_vertices, end - begin);
      EXPECT_EQ(part.halo_vertices, part.mesh.num_vertices() - part.owned_vertices);
      owned_vertices += part.owned_vertices;
      owned_tets += part.owned_tets();
      // Held: exactly the tets touching an owned vertex, in global order.
      std::vector<int> expected;
      for (int t = 0; t < whole.num_tets(); ++t)
        if (std::any_of(whole.tets[t].begin(), whole.tets[t].end(),
                        [&](int v) { return v >= begin && v < end; }))
          expected.push_back(t);
      EXPECT_EQ(part.global_tet, expected);
      if (ranks > 1) {
        EXPECT_LT(part.mesh.num_tets(), whole.num_tets());
      }
      // The local mesh is the global one renumbered: owned vertices first, in order, then the
      // halo ascending; every tet's vertices and tags map back.
      for (int v = 0; v < part.mesh.num_vertices(); ++v) {
        const int g = part.global_vertex[v];
        EXPECT_EQ(part.mesh.rest[v], whole.rest[g]);
        EXPECT_EQ(part.mesh.node_tags[v], whole.node_tags[g]);
        EXPECT_EQ(v < part.owned_vertices, g >= begin && g < end);
        if (v > part.owned_vertices) {
          EXPECT_LT(part.global_vertex[v - 1], g);
        }
      }
      for (int t = 0; t < part.mesh.num_tets(); ++t) {
        const Tet& global = whole.tets[part.global_tet[t]];
        for (int k = 0; k < 4; ++k) EXPECT_EQ(part.global_vertex[part.mesh.tets[t][k]], global[k]);
        EXPECT_EQ(part.mesh.element_tags[t], whole.element_tags[part.global_tet[t]]);
        const int smallest = *std::min_element(global.begin(), global.end());
        EXPECT_EQ(part.owned_tet[t] != 0, smallest >= begin && smallest < end);
      }
    }
    EXPECT_EQ(owned_vertices, whole.num_vertices());
    EXPECT_EQ(owned_tets, whole.num_tets());
  }
}

TEST(RankPart, ExtraRingsHoldTheTetsSharingAVertexRingByRing) {
  const TetMesh whole = make_box_mesh({3, 1, 1}, {9, 3, 3});
  for (int rank = 0; rank < 3; ++rank) {
    SCOPED_TRACE(rank);
    const RankPart base = rank_part(whole, rank, 3);
    std::set<int> expected(base.global_tet.begin(), base.global_tet.end());
    for (int rings = 1; rings <= 2; ++rings) {
      expected = ring_around(whole, expected);
      const RankPart part = rank_part(whole, rank, 3, rings);
      EXPECT_EQ(std::set<int>(part.global_tet.begin(), part.global_tet.end()), expected);
      EXPECT_EQ(part.owned_tets(), base.owned_tets());  // the rings are held, not owned
      EXPECT_EQ(part.owned_vertices, base.owned_vertices);
      EXPECT_GT(part.mesh.num_tets(), base.mesh.num_tets());
    }
  }
}

TEST(RankPart, GroupingByPartMakesEachPartContiguousAndKeepsTheMesh) {
  const TetMesh original = make_box_mesh({3, 1, 1}, {6, 2, 2});
  TetMesh mesh = original;
  std::vector<int> part(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) part[v] = (7 * v) % 3;  // scattered parts
  std::vector<int> new_index;
  const std::vector<int> start = group_vertices_by_part(mesh, part, 3, new_index);
  ASSERT_EQ(start.size(), 4u);
  EXPECT_EQ(start.front(), 0);
  EXPECT_EQ(start.back(), mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int n = new_index[v];
    EXPECT_TRUE(n >= start[part[v]] && n < start[part[v] + 1]) << v;  // inside its part's range
    EXPECT_EQ(mesh.rest[n], original.rest[v]);
    EXPECT_EQ(mesh.node_tags[n], original.node_tags[v]);
    if (v > 0 && part[v - 1] == part[v]) {
      EXPECT_EQ(new_index[v - 1] + 1, n);  // order kept
    }
  }
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(mesh.tets[t][k], new_index[original.tets[t][k]]);
}

TEST(RankPart, CutterCutsEveryPartAsRankPartOfRangeDoes) {
  // Uneven ranges, as PT-Scotch's parts make them; with rings the cutter scans per part.
  const TetMesh whole = make_box_mesh({3, 1, 1}, {9, 3, 3});
  const int nv = whole.num_vertices();
  const std::vector<int> first = {0, nv / 5, nv / 2, nv / 2 + 7, nv};
  for (int rings : {0, 1}) {
    SCOPED_TRACE(rings);
    RankPartCutter cutter(whole, first, rings);
    for (int r = 0; r + 1 < static_cast<int>(first.size()); ++r) {
      SCOPED_TRACE(r);
      const RankPart cut = cutter.cut(r);
      const RankPart expected = rank_part_of_range(whole, first[r], first[r + 1], rings);
      EXPECT_EQ(cut.global_tet, expected.global_tet);
      EXPECT_EQ(cut.global_vertex, expected.global_vertex);
      EXPECT_EQ(cut.owned_tet, expected.owned_tet);
      EXPECT_EQ(cut.halo_vertices, expected.halo_vertices);
      EXPECT_EQ(cut.mesh.tets, expected.mesh.tets);
      EXPECT_EQ(cut.mesh.rest, expected.mesh.rest);
    }
  }
}

}  // namespace
}  // namespace corofem
