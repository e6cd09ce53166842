// The procedural quadruped: a valid tet mesh with the documented extents, four hooves on the
// ground, a tet count that follows the mesh size (the report's sizes rely on it), and a kept mesh
// that is its size's.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "mesh/quadruped_mesh.hpp"
#include "mesh/vertex_selection.hpp"

namespace corofem {
namespace {

TEST(QuadrupedMesh, HasTheDocumentedShape) {
  const TetMesh mesh = make_quadruped_mesh(0.15);
  Vec3 lo = mesh.rest[0], hi = lo;
  for (const Vec3& x : mesh.rest) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  // Extents of the header: x from the hind legs' cylinders (0.15 - 0.08) to the head (2.25).
  EXPECT_NEAR(lo.x(), 0.0, 1e-9);
  EXPECT_NEAR(hi.x(), 2.25, 1e-9);
  EXPECT_NEAR(lo.y(), -0.25, 1e-9);
  EXPECT_NEAR(hi.y(), 0.25, 1e-9);
  EXPECT_NEAR(lo.z(), 0.0, 1e-9);
  EXPECT_NEAR(hi.z(), 2.08, 1e-9);
  double volume = 0;
  for (const Tet& t : mesh.tets) {
    const double v =
        signed_volume(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]);
    EXPECT_GT(v, 0);
    volume += v;
  }
  // Body 0.4 m^3, legs 4 x pi 0.08^2 x 0.05 below... the sum of the parts bounds the fused
  // volume: body 0.4 + 4 legs below the body (pi 0.08^2 1.0) + head 0.0207 + neck < pi 0.13^2 0.75.
  const double pi = 3.14159265358979;
  const double lower = 0.4 + 4 * pi * 0.0064 * 1.0 + 0.45 * 0.2 * 0.23 * 0.5;
  const double upper = 0.4 + 4 * pi * 0.0064 * 1.0 + 0.45 * 0.2 * 0.23 + pi * 0.0169 * 0.75;
  EXPECT_GT(volume, 0.98 * lower);  // faceted cylinders lose a little volume
  EXPECT_LT(volume, upper);
  for (double x : {0.15, 1.45})
    for (double y : {-0.15, 0.15})
      EXPECT_FALSE(vertices_in_box(
                       mesh.rest, {Vec3(x - 0.09, y - 0.09, -1e-9), Vec3(x + 0.09, y + 0.09, 1e-9)})
                       .empty())
          << "hoof at " << x << ", " << y;
}

TEST(QuadrupedMesh, FinerSizeGivesMoreTetsAsTheCube) {
  const int coarse = make_quadruped_mesh(0.2).num_tets();
  const int fine = make_quadruped_mesh(0.1).num_tets();
  // Halving h multiplies the count by 4 to 8 (the thin legs are resolved by MeshSizeMin first).
  EXPECT_GT(fine, 3 * coarse);
  EXPECT_LT(fine, 12 * coarse);
}

// Each size is meshed once per process and kept: asked again after another size, it must be the
// mesh of its own size, vertex for vertex, and not the other's.
TEST(QuadrupedMesh, AKeptMeshIsTheMeshOfItsSize) {
  const TetMesh first = make_quadruped_mesh(0.2);
  const TetMesh other = make_quadruped_mesh(0.17);
  const TetMesh again = make_quadruped_mesh(0.2);
  ASSERT_NE(other.num_tets(), first.num_tets());
  ASSERT_EQ(again.num_tets(), first.num_tets());
  ASSERT_EQ(again.num_vertices(), first.num_vertices());
  EXPECT_EQ(again.tets, first.tets);
  EXPECT_EQ(again.rest, first.rest);
  EXPECT_EQ(again.node_tags, first.node_tags);
}

TEST(QuadrupedMesh, RejectsBadSize) {
  EXPECT_THROW(make_quadruped_mesh(0), InputError);
  EXPECT_THROW(make_quadruped_mesh(-1), InputError);
}

}  // namespace
}  // namespace corofem
