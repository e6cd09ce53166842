// The edge stretch that bounds static Newton steps, against fields whose answer is known.
#include <gtest/gtest.h>

#include "fem/edge_stretch.hpp"
#include "mesh/box_mesh.hpp"

namespace corofem {
namespace {

TEST(EdgeStretch, RigidTranslationIsZeroAndUniformStretchIsItsStrain) {
  const TetMesh mesh = make_box_mesh({2, 1, 1}, {4, 2, 2});
  Eigen::VectorXd du(3 * mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) du.segment<3>(3 * v) = Vec3(0.3, -1, 2);
  EXPECT_NEAR(largest_edge_stretch(mesh, du), 0, 1e-15);
  // du = 0.25 x along x: an edge along x changes by 0.25 of its length, any other by less.
  for (int v = 0; v < mesh.num_vertices(); ++v)
    du.segment<3>(3 * v) = Vec3(0.25 * mesh.rest[v].x(), 0, 0);
  EXPECT_NEAR(largest_edge_stretch(mesh, du), 0.25, 1e-14);
  // One vertex moved by d: its shortest edge (0.5, the cells' side) changes by |d|.
  du.setZero();
  du.segment<3>(0) = Vec3(0, 0, 0.1);
  EXPECT_NEAR(largest_edge_stretch(mesh, du), 0.1 / 0.5, 1e-14);
}

}  // namespace
}  // namespace corofem
