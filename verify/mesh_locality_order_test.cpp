// Locality order: a permutation of vertices and tets that changes nothing physical. The same
// static solve on the quadruped, with and without reordering, agrees node tag by node tag.
#include <gtest/gtest.h>

#include <map>

#include "scene/scene_simulation.hpp"

namespace corofem {
namespace {

nlohmann::json quadruped_scene(bool reorder) {
  return {{"mesh", {{"shape", "quadruped"}, {"size", 0.2}, {"reorder", reorder}}},
          {"material", {{"young", 1e6}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, -0.3, -0.01}, {0.3, 0.3, 0.05}}}}}},
          {"gravity", {0, 0, -9.81}},
          {"analysis", {{"type", "static"}, {"formulation", "linear"}, {"solver", "cholmod"}}}};
}

TEST(LocalityOrder, SolutionIsTheSameNodeByNode) {
  SceneSimulation plain(parse_scene(quadruped_scene(false), ".", "plain"));
  SceneSimulation sorted(parse_scene(quadruped_scene(true), ".", "sorted"));
  const SimulationResult a = plain.run(), b = sorted.run();
  const TetMesh& ma = plain.problem().mesh;
  const TetMesh& mb = sorted.problem().mesh;
  ASSERT_EQ(ma.num_vertices(), mb.num_vertices());
  ASSERT_EQ(ma.num_tets(), mb.num_tets());
  std::map<std::size_t, int> index_of;
  for (int v = 0; v < mb.num_vertices(); ++v) index_of[mb.node_tags[v]] = v;
  ASSERT_EQ(index_of.size(), static_cast<std::size_t>(mb.num_vertices()));  // a permutation
  bool moved = false;
  for (int v = 0; v < ma.num_vertices(); ++v) {
    const int w = index_of.at(ma.node_tags[v]);
    moved |= w != v;
    EXPECT_EQ(ma.rest[v], mb.rest[w]);
    // Same system up to the order of summation: rounding-level differences only.
    EXPECT_LT((a.displacement.segment<3>(3 * v) - b.displacement.segment<3>(3 * w)).norm(),
              1e-9 * a.displacement.lpNorm<Eigen::Infinity>());
  }
  EXPECT_TRUE(moved) << "the order did not change: the test proves nothing";
  // Consecutive vertices are close: the mean distance between index neighbours drops.
  auto mean_step = [](const TetMesh& m) {
    double sum = 0;
    for (int v = 1; v < m.num_vertices(); ++v) sum += (m.rest[v] - m.rest[v - 1]).norm();
    return sum / (m.num_vertices() - 1);
  };
  EXPECT_LT(mean_step(mb), 0.5 * mean_step(ma));
}

}  // namespace
}  // namespace corofem
