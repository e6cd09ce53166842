// Patch test: an affine displacement imposed on the boundary of a box is reproduced exactly inside
// (linear tets represent affine fields exactly; only solver round-off remains).
#include <gtest/gtest.h>

#include "fem/fe_problem.hpp"
#include "integrate/static_solver.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {
namespace {

TEST(PatchTest, AffineBoundaryDisplacementReproducedInside) {
  const Vec3 size(1.0, 0.7, 0.4);
  TetMesh mesh = make_box_mesh(size, {5, 4, 3});
  std::vector<Material> m(mesh.tets.size(), Material{3e4, 0.3, 1});
  FeProblem p = make_fe_problem(std::move(mesh), std::move(m));
  Mat3 a;
  a << 0.01, -0.02, 0.005, 0.003, 0.02, -0.01, 0.0, 0.015, -0.007;
  const Vec3 b(0.1, -0.2, 0.05);
  int interior = 0;
  for (int v = 0; v < p.mesh.num_vertices(); ++v) {
    const Vec3& x = p.mesh.rest[v];
    const bool boundary = (x.array() < 1e-12).any() || (x.array() > size.array() - 1e-12).any();
    if (boundary)
      p.dirichlet.fix_vertex(v, a * x + b);
    else
      ++interior;
  }
  ASSERT_GT(interior, 10);
  IdentityExtractor none;
  auto solver = make_cholmod_solver();
  const SimulationResult r = solve_static(p, none, *solver, {false, 1, 1e-10, 1});
  double worst = 0;
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    worst = std::max(worst, (r.displacement.segment<3>(3 * v) - (a * p.mesh.rest[v] + b)).norm());
  EXPECT_LT(worst, 1e-10 * (a.norm() + b.norm()));
}

}  // namespace
}  // namespace corofem
