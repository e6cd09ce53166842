// A surface's shells and their nesting against arrangements of cubes whose answer is known: side
// by side, nested three deep, and an STL's unshared vertices.
#include <gtest/gtest.h>

#include <utility>

#include "mesh/surface_shells.hpp"

namespace corofem {
namespace {

/// Appends the 12 outward triangles of the cube [origin, origin + side]^3, with its 8 corners as
/// vertices of their own, or with 3 vertices per triangle (`unshared`, as an STL stores them).
void add_cube(SurfaceMesh& s, const Vec3& origin, double side, bool unshared = false) {
  const int first = s.num_vertices();
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(origin + side * Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<std::array<int, 3>> triangles;
  for (const auto& q : quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  if (!unshared) {
    for (const Vec3& c : corners) s.points.push_back(c);
    for (const auto& t : triangles)
      s.triangles.push_back({first + t[0], first + t[1], first + t[2]});
    return;
  }
  for (const auto& t : triangles) {
    const int v = s.num_vertices();
    for (int k = 0; k < 3; ++k) s.points.push_back(corners[t[k]]);
    s.triangles.push_back({v, v + 1, v + 2});
  }
}

TEST(SurfaceShells, OneCubeIsOneShellEvenWithAnStlsUnsharedVertices) {
  for (const bool unshared : {false, true}) {
    SurfaceMesh s;
    add_cube(s, Vec3::Zero(), 1, unshared);
    const auto shells = surface_shells(s);
    ASSERT_EQ(shells.size(), 1u) << unshared;
    EXPECT_EQ(shells[0].surface.num_vertices(), 8);  // welded
    EXPECT_EQ(shells[0].surface.triangles.size(), 12u);
    EXPECT_NEAR(enclosed_volume(shells[0].surface), 1.0, 1e-14);  // orientation kept
    EXPECT_EQ(shells[0].depth, 0);
    EXPECT_EQ(shells[0].inside, -1);
  }
}

TEST(SurfaceShells, NestingDepthAndImmediateEncloser) {
  // A cube of side 8 holding one of side 4 holding one of side 2; beside them a unit cube, and
  // a unit cube in the side-8 cube but outside the side-4 one. Listed out of order.
  SurfaceMesh s;
  add_cube(s, Vec3(2, 2, 2), 2);         // 0: inside 2, inside 1
  add_cube(s, Vec3(1, 1, 1), 4);         // 1: inside 2
  add_cube(s, Vec3::Zero(), 8);          // 2: outermost
  add_cube(s, Vec3(10, 0, 0), 1, true);  // 3: beside
  add_cube(s, Vec3(6, 6, 6), 1);         // 4: inside 2 only
  const int depth[] = {2, 1, 0, 0, 1}, inside[] = {1, 2, -1, -1, 2};
  // The same nesting whatever the triangles' orientation: as given (all outward), and with the
  // side-4 cube's turned inward, as an STL's void should face.
  for (const bool void_faces_inward : {false, true}) {
    SCOPED_TRACE(void_faces_inward ? "void faces inward" : "all outward");
    if (void_faces_inward)
      for (std::size_t t = 12; t < 24; ++t) std::swap(s.triangles[t][1], s.triangles[t][2]);
    const auto shells = surface_shells(s);
    ASSERT_EQ(shells.size(), 5u);
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(shells[i].depth, depth[i]) << i;
      EXPECT_EQ(shells[i].inside, inside[i]) << i;
    }
  }
}

TEST(SurfaceShells, FilledVolumeSubtractsVoidsWhicheverWayTrianglesFace) {
  // The arrangement above: bodies of depth 0 and 2 (sides 8, 1 beside, 2), voids of depth 1
  // (sides 4, 1): 512 + 1 + 8 - 64 - 1. The divergence theorem's sum is exact for cubes, to
  // round-off.
  SurfaceMesh s;
  add_cube(s, Vec3(2, 2, 2), 2);
  add_cube(s, Vec3(1, 1, 1), 4);
  add_cube(s, Vec3::Zero(), 8);
  add_cube(s, Vec3(10, 0, 0), 1, true);
  add_cube(s, Vec3(6, 6, 6), 1);
  EXPECT_NEAR(filled_volume(surface_shells(s)), 456.0, 1e-12 * 512);
  // Every third triangle turned over (an STL with flipped facets, which gmsh meshes as well):
  // each shell's triangles are made to agree before summing. Without that the sum is wrong.
  for (std::size_t t = 0; t < s.triangles.size(); t += 3)
    std::swap(s.triangles[t][1], s.triangles[t][2]);
  EXPECT_NEAR(filled_volume(surface_shells(s)), 456.0, 1e-12 * 512);
  // All of the side-8 cube's turned inward.
  for (std::size_t t = 24; t < 36; ++t) std::swap(s.triangles[t][1], s.triangles[t][2]);
  EXPECT_NEAR(filled_volume(surface_shells(s)), 456.0, 1e-12 * 512);
}

}  // namespace
}  // namespace corofem
