// Connected parts of a tet mesh against meshes whose pieces are known: one box, and two boxes side
// by side in one mesh that share no vertex.
#include <gtest/gtest.h>

#include "mesh/box_mesh.hpp"
#include "mesh/connected_parts.hpp"

namespace corofem {
namespace {

TEST(ConnectedParts, OneBoxIsOnePart) {
  const TetMesh box = make_box_mesh({1, 1, 1}, {3, 2, 2});
  const ConnectedParts parts = connected_parts(box);
  EXPECT_EQ(parts.count, 1);
  for (int part : parts.of_vertex) EXPECT_EQ(part, 0);
}

TEST(ConnectedParts, TwoBoxesInOneMeshAreTwoPartsEachItsOwnVertices) {
  // The second box's vertices follow the first's, shifted clear of it: two parts, the first
  // box's vertices all in part 0 and the second's in part 1. A tet joining them makes one.
  TetMesh mesh = make_box_mesh({1, 1, 1}, {2, 2, 2});
  const TetMesh second = make_box_mesh({1, 1, 1}, {3, 1, 2});
  const int offset = mesh.num_vertices();
  for (const Vec3& p : second.rest) mesh.rest.push_back(p + Vec3(5, 0, 0));
  for (Tet t : second.tets) {
    for (int& v : t) v += offset;
    mesh.tets.push_back(t);
  }
  const ConnectedParts parts = connected_parts(mesh);
  ASSERT_EQ(parts.count, 2);
  for (int v = 0; v < mesh.num_vertices(); ++v) EXPECT_EQ(parts.of_vertex[v], v < offset ? 0 : 1);
  mesh.tets.push_back({0, 1, 2, offset});
  EXPECT_EQ(connected_parts(mesh).count, 1);
}

}  // namespace
}  // namespace corofem
