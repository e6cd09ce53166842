// Generated box: volume, orientation, and conformity (every interior face shared by two tets).
#include <gtest/gtest.h>

#include <map>

#include "mesh/box_mesh.hpp"

namespace corofem {
namespace {

TEST(BoxMesh, VolumeOrientationAndConformity) {
  const Vec3 size(2.0, 1.0, 0.5);
  const TetMesh mesh = make_box_mesh(size, {4, 3, 2});
  EXPECT_EQ(mesh.num_tets(), 6 * 4 * 3 * 2);
  EXPECT_EQ(mesh.num_vertices(), 5 * 4 * 3);
  double volume = 0;
  std::map<std::array<int, 3>, int> faces;
  for (const Tet& t : mesh.tets) {
    const double v =
        signed_volume(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]);
    EXPECT_GT(v, 0);
    volume += v;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      int n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[n++] = t[a];
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  EXPECT_NEAR(volume, size.prod(), 1e-14 * size.prod());
  // Conforming: each face is shared by at most 2 tets; the boundary faces (used once) tile the
  // box surface: 2 triangles per boundary cell face.
  int boundary = 0;
  for (const auto& [f, count] : faces) {
    EXPECT_LE(count, 2);
    boundary += count == 1;
  }
  EXPECT_EQ(boundary, 2 * 2 * (4 * 3 + 3 * 2 + 4 * 2));
}

TEST(BoxMesh, RejectsEmptyCounts) {
  EXPECT_THROW(make_box_mesh({1, 1, 1}, {0, 1, 1}), std::exception);
}

}  // namespace
}  // namespace corofem
