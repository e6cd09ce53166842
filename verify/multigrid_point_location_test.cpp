// Point location and the mesh-level transfer: inside points get non-negative barycentric
// coordinates summing to 1, outside points the nearest tet (checked by brute force), and the
// interpolation reproduces random affine fields exactly inside and outside; a coarse mesh that
// does not cover the level above is refused.
#include <gtest/gtest.h>

#include <random>

#include "core/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "multigrid/mesh_level.hpp"
#include "multigrid/point_location.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// Distance from p to tet t by brute force: 0 inside, else the minimum over a dense sampling
/// of its faces' closest points (a sampled upper bound, exact within the sampling step).
double sampled_distance(const TetMesh& m, int t, const Vec3& p) {
  const Tet& tet = m.tets[t];
  double best = std::numeric_limits<double>::infinity();
  constexpr int n = 60;
  static constexpr int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& f : faces)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = double(i) / n, v = double(j) / n;
        const Vec3 q =
            (1 - u - v) * m.rest[tet[f[0]]] + u * m.rest[tet[f[1]]] + v * m.rest[tet[f[2]]];
        best = std::min(best, (p - q).norm());
      }
  return best;
}

TEST(PointLocation, InsidePointsGetTheirContainingTet) {
  test::TempDir dir;
  test::write_text(dir / "cube.stl", test::cube_stl(3));
  const TetMesh coarse = tetrahedralize_surface(dir / "cube.stl", 0.4);
  const TetLocator locator(coarse.rest, coarse.tets);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.001, 0.999);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    const TetLocation where = locator.locate(p);
    ASSERT_GE(where.tet, 0);
    EXPECT_EQ(where.distance, 0);
    double sum = 0;
    Vec3 back = Vec3::Zero();
    for (int v = 0; v < 4; ++v) {
      EXPECT_GE(where.weights[v], 0);
      sum += where.weights[v];
      back += where.weights[v] * coarse.rest[coarse.tets[where.tet][v]];
    }
    EXPECT_NEAR(sum, 1, 1e-12);
    EXPECT_LT((back - p).norm(), 1e-12);  // the coordinates reproduce the point: p is inside
  }
}

TEST(PointLocation, OutsidePointsGetTheNearestTet) {
  const TetMesh coarse = make_box_mesh({1, 1, 1}, {3, 3, 3});
  const TetLocator locator(coarse.rest, coarse.tets);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.4, 1.4);
  int outside = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    const TetLocation where = locator.locate(p);
    if (where.distance == 0) continue;
    ++outside;
    // The nearest tet: no tet is closer than the located one (sampled faces: within 2% of an
    // edge of 1/3, the sampling step).
    double best = std::numeric_limits<double>::infinity();
    for (int t = 0; t < coarse.num_tets(); ++t)
      best = std::min(best, sampled_distance(coarse, t, p));
    EXPECT_LE(where.distance, best + 1e-12);
    EXPECT_GE(where.distance, best - 0.01);
    // The distance is that of the box (the mesh is the whole box).
    const Vec3 clamped = p.cwiseMax(Vec3::Zero()).cwiseMin(Vec3::Ones());
    EXPECT_NEAR(where.distance, (p - clamped).norm(), 1e-12);
  }
  EXPECT_GT(outside, 100);
}

TEST(MeshLevel, RowsSumToOneAndReproduceAffineFieldsInsideAndOutside) {
  // The fine mesh reaches past the coarse one on every side (a coarse surface loses volume), so
  // some fine vertices are extrapolated: their weights may be negative, and still exact.
  test::TempDir dir;
  test::write_text(dir / "cube.stl", test::cube_stl(3));
  const TetMesh coarse = tetrahedralize_surface(dir / "cube.stl", 0.4);
  TetMesh fine = make_box_mesh({1.1, 1.1, 1.1}, {11, 11, 11});
  for (Vec3& x : fine.rest) x -= Vec3::Constant(0.05);
  std::vector<char> fixed(fine.rest.size(), 0);
  fixed[0] = fixed[5] = 1;
  MeshLevelFit fit;
  const CoarseLevel level = make_mesh_level(fine.rest, fixed, coarse, "cube", &fit);
  const Transfer& t = level.transfer;
  EXPECT_GT(fit.outside, 0);
  EXPECT_EQ(fit.located, fine.num_vertices() - 2);
  EXPECT_EQ(t.coarse + fit.dropped_vertices, coarse.num_vertices());
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 5; ++trial) {
    const double c0 = g(rng);
    const Vec3 c(g(rng), g(rng), g(rng));
    auto f = [&](const Vec3& x) { return c0 + c.dot(x); };
    double scale = 0;
    for (const Vec3& x : fine.rest) scale = std::max(scale, std::abs(f(x)));
    int negative = 0;
    for (int l = 0; l < t.fine; ++l) {
      if (fixed[l]) {
        EXPECT_EQ(t.p_start[l + 1], t.p_start[l]);  // fixed: no weights
        continue;
      }
      double sum = 0, value = 0;
      for (int k = t.p_start[l]; k < t.p_start[l + 1]; ++k) {
        sum += t.p_weight[k];
        value += t.p_weight[k] * f(level.points[t.p_col[k]]);
        negative += t.p_weight[k] < 0;
      }
      EXPECT_NEAR(sum, 1, 1e-12);
      EXPECT_NEAR(value, f(fine.rest[l]), 1e-12 * scale);
    }
    EXPECT_GT(negative, 0);  // extrapolation happened and was exact
  }
  // Restriction and prolongation are transposes: <R x, y> = <x, R^T y>.
  Eigen::VectorXd x = Eigen::VectorXd::Random(3 * t.fine),
                  y = Eigen::VectorXd::Random(3 * t.coarse);
  Eigen::VectorXd rx, pty = Eigen::VectorXd::Zero(3 * t.fine);
  t.restrict_to(x, rx);
  t.prolongate_add(y, pty);
  EXPECT_NEAR(rx.dot(y), x.dot(pty), 1e-12 * rx.norm() * y.norm());
}

TEST(MeshLevel, CoarseMeshThatDoesNotCoverTheLevelAboveIsAnError) {
  const TetMesh fine = make_box_mesh({1, 1, 1}, {6, 6, 6});
  TetMesh away = make_box_mesh({1, 1, 1}, {2, 2, 2});
  for (Vec3& x : away.rest) x += Vec3(5, 0, 0);
  away.source = "away.msh";
  try {
    make_mesh_level(fine.rest, {}, away, away.source);
    FAIL() << "a disjoint coarse mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("away.msh"), std::string::npos) << e.what();
  }
  TetMesh half = make_box_mesh({0.4, 1, 1}, {2, 4, 4});  // covers 40% of the points
  EXPECT_THROW(make_mesh_level(fine.rest, {}, half, "half"), InputError);
}

}  // namespace
}  // namespace corofem
