// What rank 0 hands each rank of a distributed run (issue 37): its part of the body, checked
// against the body in the scene's own vertex order, and the bytes it travels as.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "scene/rank_share.hpp"

namespace corofem {
namespace {

/// A box's body with a material per tet, supports on x = 0 and a force on every DOF, all
/// different, in the scene's vertex order.
SceneBody test_body() {
  SceneBody body;
  body.mesh = make_box_mesh({3, 1, 1}, {6, 2, 2});
  for (int t = 0; t < body.mesh.num_tets(); ++t)
    body.materials.push_back(Material{1e5 + t, 0.3, 1000.0 + t});
  for (int v = 0; v < body.mesh.num_vertices(); ++v)
    if (body.mesh.rest[v].x() == 0) body.fixed_vertices.push_back(v);
  body.external_force = Eigen::VectorXd::LinSpaced(3 * body.mesh.num_vertices(), -1, 2);
  return body;
}

/// A transfer with rows of different lengths: fine vertex l to coarse vertices l % 5 .. .
Transfer test_transfer(int fine) {
  Transfer t;
  t.fine = fine;
  t.coarse = 5;
  t.p_start = {0};
  for (int l = 0; l < fine; ++l) {
    for (int i = 0; i <= l % 3; ++i) {
      t.p_col.push_back((l + i) % 5);
      t.p_weight.push_back(0.1 * l + i);
    }
    t.p_start.push_back(static_cast<int>(t.p_col.size()));
  }
  return t;
}

/// slice's row v is t's row of fine vertex vertices[v], for every v.
void expect_same_rows(const Transfer& slice, const Transfer& t, const std::vector<int>& vertices) {
  ASSERT_EQ(slice.p_start.size(), vertices.size() + 1);
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const int l = vertices[v], length = t.p_start[l + 1] - t.p_start[l];
    ASSERT_EQ(slice.p_start[v + 1] - slice.p_start[v], length);
    for (int k = 0; k < length; ++k) {
      EXPECT_EQ(slice.p_col[slice.p_start[v] + k], t.p_col[t.p_start[l] + k]);
      EXPECT_EQ(slice.p_weight[slice.p_start[v] + k], t.p_weight[t.p_start[l] + k]);
    }
  }
}

std::vector<int> all_vertices(int count) {
  std::vector<int> v(count);
  for (int l = 0; l < count; ++l) v[l] = l;
  return v;
}

TEST(RankShare, EachRankGetsItsVerticesLoadsSupportsAndMaterialsAsTheSceneHadThem) {
  const SceneBody scene_order = test_body();
  SceneBody whole = test_body();
  const int nv = whole.mesh.num_vertices(), ranks = 3;
  std::vector<int> part_of_vertex(nv), new_index;
  for (int v = 0; v < nv; ++v) part_of_vertex[v] = (7 * v) % ranks;  // scattered parts
  const std::vector<int> first =
      group_vertices_by_part(whole.mesh, part_of_vertex, ranks, new_index);
  renumber_supports_and_loads(whole, new_index);
  const std::vector<Transfer> transfers = {test_transfer(nv), test_transfer(40)};
  std::vector<int> scene_vertex(nv);
  for (int v = 0; v < nv; ++v) scene_vertex[new_index[v]] = v;
  RankPartCutter cutter(whole.mesh, first);
  int owned = 0;
  for (int r = 0; r < ranks; ++r) {
    SCOPED_TRACE(r);
    const RankShare share = make_rank_share(whole, scene_vertex, cutter.cut(r), transfers);
    const RankPart& part = share.part;
    ASSERT_EQ(part.owned_vertices, first[r + 1] - first[r]);
    ASSERT_GT(part.halo_vertices, 0);  // so that the transfer's halo rows are checked
    owned += part.owned_vertices;
    ASSERT_EQ(share.scene_vertex_index.size(), static_cast<std::size_t>(part.owned_vertices));
    const std::vector<int>& fixed = share.body.fixed_vertices;
    for (int v = 0; v < share.body.mesh.num_vertices(); ++v) {
      const int g = part.global_vertex[v];
      int s = -1;  // the scene's number of global vertex g
      for (int u = 0; u < nv; ++u)
        if (new_index[u] == g) s = u;
      ASSERT_GE(s, 0);
      if (v < part.owned_vertices) {
        EXPECT_EQ(share.scene_vertex_index[v], s);
      }
      EXPECT_EQ(share.body.mesh.rest[v], scene_order.mesh.rest[s]);
      EXPECT_EQ(share.body.external_force.segment<3>(3 * v),
                scene_order.external_force.segment<3>(3 * s));
      const bool scene_fixed = std::binary_search(scene_order.fixed_vertices.begin(),
                                                  scene_order.fixed_vertices.end(), s);
      EXPECT_EQ(std::binary_search(fixed.begin(), fixed.end(), v), scene_fixed);
    }
    for (int t = 0; t < share.body.mesh.num_tets(); ++t)
      EXPECT_EQ(share.body.materials[t].young, scene_order.materials[part.global_tet[t]].young);
    ASSERT_EQ(share.transfers.size(), 2u);
    // The finest transfer's rows of the part's vertices, owned (where a slice from first[r]
    // has them) then halo; the coarser levels whole.
    EXPECT_EQ(share.transfers[0].first_row, first[r]);
    expect_same_rows(share.transfers[0], transfers[0], part.global_vertex);
    EXPECT_EQ(share.transfers[1].first_row, 0);
    expect_same_rows(share.transfers[1], transfers[1], all_vertices(40));
  }
  EXPECT_EQ(owned, nv);
}

TEST(RankShare, TravelsAsBytesUnchangedAndShortBytesAreAFault) {
  SceneBody whole = test_body();
  std::vector<int> scene_vertex(whole.mesh.num_vertices());
  for (int v = 0; v < whole.mesh.num_vertices(); ++v) scene_vertex[v] = v;
  const int half = whole.mesh.num_vertices() / 2;
  const RankShare share = make_rank_share(
      whole, scene_vertex, rank_part_of_range(whole.mesh, half, scene_vertex.size(), 1),
      {test_transfer(80)});
  const std::vector<char> bytes = pack_rank_share(share);
  const RankShare back = unpack_rank_share(bytes);
  EXPECT_EQ(back.part.global_vertex, share.part.global_vertex);
  EXPECT_EQ(back.part.global_tet, share.part.global_tet);
  EXPECT_EQ(back.part.owned_tet, share.part.owned_tet);
  EXPECT_EQ(back.part.owned_vertices, share.part.owned_vertices);
  EXPECT_EQ(back.part.halo_vertices, share.part.halo_vertices);
  EXPECT_EQ(back.part.first_vertex, half);
  EXPECT_EQ(back.part.global_vertices, whole.mesh.num_vertices());
  EXPECT_EQ(back.part.global_tets, whole.mesh.num_tets());
  EXPECT_EQ(back.body.mesh.rest, share.body.mesh.rest);
  EXPECT_EQ(back.body.mesh.tets, share.body.mesh.tets);
  EXPECT_EQ(back.body.mesh.node_tags, share.body.mesh.node_tags);
  EXPECT_EQ(back.body.mesh.source, share.body.mesh.source);
  ASSERT_EQ(back.body.materials.size(), share.body.materials.size());
  for (std::size_t t = 0; t < back.body.materials.size(); ++t)
    EXPECT_EQ(back.body.materials[t].density, share.body.materials[t].density);
  EXPECT_EQ(back.body.fixed_vertices, share.body.fixed_vertices);
  EXPECT_EQ(back.body.external_force, share.body.external_force);
  EXPECT_EQ(back.scene_vertex_index, share.scene_vertex_index);
  ASSERT_EQ(back.transfers.size(), 1u);
  EXPECT_EQ(back.transfers[0].first_row, half);
  EXPECT_EQ(back.transfers[0].p_start, share.transfers[0].p_start);
  EXPECT_EQ(back.transfers[0].p_weight, share.transfers[0].p_weight);
  // A message cut short is a fault that says what it was, not a read past its end.
  std::vector<char> cut(bytes.begin(), bytes.end() - 5);
  try {
    unpack_rank_share(cut);
    ADD_FAILURE() << "short bytes were read";
  } catch (const NumericalFault& e) {
    EXPECT_NE(std::string(e.what()).find("a rank's part of the mesh"), std::string::npos);
  }
}

}  // namespace
}  // namespace corofem
