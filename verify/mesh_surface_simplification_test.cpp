// Surface coarsening for the coarse meshes of a bare surface (mesh/surface_simplification.hpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <numbers>

#include "mesh/coarse_surface_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/surface_simplification.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::TempDir;
using test::write_text;

/// An icosahedron's faces split `levels` times, projected onto the unit sphere (outward).
SurfaceMesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  SurfaceMesh s;
  for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    s.points.push_back(p.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = middle.try_emplace(key, s.num_vertices());
      if (added) s.points.push_back((s.points[a] + s.points[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : s.triangles) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    s.triangles = finer;
  }
  return s;
}

/// Every directed edge once and its reverse once: closed, 2-manifold, consistently oriented.
void expect_closed_oriented(const SurfaceMesh& s) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : s.triangles) {
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) << "degenerate triangle";
    for (int c = 0; c < 3; ++c) ++directed[{t[c], t[(c + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " on the boundary";
  }
  // Euler: V - E + F = 2 for a sphere (genus 0).
  EXPECT_EQ(s.num_vertices() - static_cast<int>(directed.size()) / 2 +
                static_cast<int>(s.triangles.size()),
            2);
}

TEST(SurfaceSimplification, SphereStaysAClosedOrientedSurfaceOfNearlyItsVolume) {
  const SurfaceMesh fine = icosphere(4);  // 2562 vertices
  const double volume = enclosed_volume(fine);
  SimplificationStats stats;
  const SurfaceMesh coarse = simplify_surface(fine, fine.num_vertices() / 16, &stats);
  EXPECT_EQ(coarse.num_vertices(), fine.num_vertices() / 16);
  EXPECT_EQ(stats.collapses, fine.num_vertices() - coarse.num_vertices());
  expect_closed_oriented(coarse);
  // 160 vertices of a unit sphere: an inscribed polyhedron with edges ~0.3 loses some 3% of
  // 4/3 pi; the quadrics keep vertices near the tangent planes, so the change stays below 5%.
  EXPECT_NEAR(enclosed_volume(coarse) / volume, 1.0, 0.05);
  // No folds: every triangle faces outward (its normal along its centroid's direction).
  for (const auto& t : coarse.triangles) {
    const Vec3 n = (coarse.points[t[1]] - coarse.points[t[0]])
                       .cross(coarse.points[t[2]] - coarse.points[t[0]]);
    EXPECT_GT(n.normalized().dot(
                  (coarse.points[t[0]] + coarse.points[t[1]] + coarse.points[t[2]]).normalized()),
              0.5);
  }
}

TEST(SurfaceSimplification, CubeKeepsItsFacesEdgesAndCornersExactly) {
  // A collapse inside a face has zero error and its optimal point stays in the face's plane; on
  // an edge, on both planes; the corners, on three, cannot move: the volume stays 1 to round-off.
  TempDir dir;
  write_text(dir / "cube.stl", test::cube_stl(8));
  const SurfaceMesh fine = read_surface(dir / "cube.stl");
  ASSERT_EQ(fine.num_vertices(), 6 * 8 * 8 + 2);
  EXPECT_NEAR(enclosed_volume(fine), 1.0, 1e-12);
  const SurfaceMesh coarse = simplify_surface(fine, 40);
  EXPECT_LE(coarse.num_vertices(), 40);
  expect_closed_oriented(coarse);
  EXPECT_NEAR(enclosed_volume(coarse), 1.0, 1e-9);
  EXPECT_NEAR(surface_area(coarse), 6.0, 1e-9);
}

TEST(SurfaceSimplification, CoarsenedSurfaceMeshIsCoarser) {
  // gmsh keeps a surface's triangles: at size 0.25 the cube's 8x8 faces (386 surface vertices,
  // most of this small mesh's) would stay; coarsened to the size, the surface keeps
  // 6 / (sqrt(3)/2 0.25^2) = 111 vertices, and the volume mesh is more than 3x smaller.
  TempDir dir;
  write_text(dir / "cube.stl", test::cube_stl(8));
  const TetMesh kept = tetrahedralize_surface(dir / "cube.stl", 0.25);
  const TetMesh coarsened = tetrahedralize_coarsened_surface(dir / "cube.stl", 0.25);
  EXPECT_LT(3 * coarsened.num_vertices(), kept.num_vertices())
      << kept.num_vertices() << " against " << coarsened.num_vertices();
  double volume = 0;
  for (const Tet& t : coarsened.tets)
    volume += signed_volume(coarsened.rest[t[0]], coarsened.rest[t[1]], coarsened.rest[t[2]],
                            coarsened.rest[t[3]]);
  EXPECT_NEAR(volume, 1.0, 1e-9);
  EXPECT_NE(coarsened.source.find("surface coarsened from 386 to"), std::string::npos)
      << coarsened.source;
}

}  // namespace
}  // namespace corofem
