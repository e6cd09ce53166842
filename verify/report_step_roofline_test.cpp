// The roofline's byte counts (report/step_roofline.hpp) against counts made here from the mesh
// alone: on a box the pattern has one block per pair of vertices sharing a tet, the hierarchy's
// stream and matrices have the sizes the multigrid reports, and the solve's traffic grows by
// exactly one iteration's worth per iteration.
#include <gtest/gtest.h>

#include <set>

#include "core/threads.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "report/step_roofline.hpp"
#include "rotation/element_quadrature.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {
namespace {

nlohmann::json box_scene() {
  return {{"mesh", {{"box", {1, 1, 1}}, {"cells", {4, 4, 4}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 1, 1}}}}}},
          {"analysis",
           {{"type", "dynamic"},
            {"solver", "mgpcg"},
            {"levels", 2},
            {"hierarchy", "lattice"},
            {"rotation", "energy-newton"},
            {"steps", 1},
            {"dt", 0.01}}}};
}

TEST(StepRoofline, BytesFollowFromTheMeshAndTheHierarchy) {
  const ScopedThreadCount one(1);  // the update phase in full (two threads: below)
  SceneSimulation sim(parse_scene(box_scene(), ".", "box"));
  sim.run();  // one step: the hierarchy holds a system matrix
  const auto& solver = dynamic_cast<const MultigridSolver&>(sim.solver());
  const FeProblem& problem = sim.problem();
  const double e = problem.mesh.num_tets(), v = problem.mesh.num_vertices(), n = 3 * v;
  ASSERT_EQ(v, 125);  // 5 x 5 x 5 vertices
  // One block per ordered pair of vertices sharing a tet (the diagonal included).
  std::set<std::pair<int, int>> pairs;
  for (const Tet& t : problem.mesh.tets)
    for (int a : t)
      for (int b : t) pairs.insert({a, b});
  const double blocks = static_cast<double>(pairs.size());
  const auto t = step_traffic(problem, solver, 2.0, 5.0);
  // system: the assembly wrote A; the velocity's prescribed values (flags, two vectors read, one
  // written), the vertex flags, the supported vertices' rows and columns (each block read and
  // written, 72 B, with its 4 B index), b in and out. The fixed face x = 0 has 25 vertices.
  double supported = 0;
  for (int i = 0; i < problem.mesh.num_vertices(); ++i)
    if (problem.mesh.rest[i].x() < 1e-9)
      supported += 2 * (problem.stiffness.row_start[i + 1] - problem.stiffness.row_start[i]);
  EXPECT_GT(supported, 0);
  EXPECT_DOUBLE_EQ(t.at("system").bytes, n + 24 * n + n + 148 * supported + 16 * n);
  // rotate: positions built (rest, u in; p out) and gathered, tets, quadrature offsets, rotations
  // in and out.
  EXPECT_DOUBLE_EQ(t.at("rotate").bytes,
                   72 * v + 16 * e + 24 * v + sizeof(MomentArms) * e + 144 * e);
  // assemble: A written once, the mass and u read, the force written, the rest positions, 16
  // targets and 4 vertex ids per tet, Q, and the gradients with V lambda, V mu (112 B in 2 lines).
  EXPECT_DOUBLE_EQ(t.at("assemble").bytes,
                   72 * blocks + 8 * n + 8 * n + 8 * n + 24 * v + e * (72 + 128 + 64 + 16));
  // forces: b = M v + dt (f_ext - f_int), four vectors read and one written.
  EXPECT_DOUBLE_EQ(t.at("forces").bytes, 40 * n);
  // update: the gather stream (the default method), A read, E written (the fine values are swapped
  // in, not copied).
  const MultigridHierarchy& h = solver.hierarchy();
  ASSERT_EQ(h.num_levels(), 2);
  const double coarse_blocks = static_cast<double>(h.matrix(1).col_index.size());
  EXPECT_GE(t.at("update").bytes,
            static_cast<double>(h.gather(0).bytes()) + 72 * blocks + 72 * coarse_blocks);
  ASSERT_EQ(solver.params().galerkin, GalerkinMethod::Gather);
  EXPECT_GT(solver.coarsest_factorization_flops(), 0);
  // One update, which factorized the coarsest level, after the check of how far its values
  // moved (3 flops a value, 9 values a block).
  const MultigridSummary summary = *sim.multigrid_summary(sim.solver());
  ASSERT_EQ(summary.updates, 1);
  ASSERT_EQ(summary.coarsest_factorizations, 1);
  EXPECT_DOUBLE_EQ(t.at("update").flops, 18.0 * static_cast<double>(h.gather(0).num_pairs()) +
                                             50 * v + solver.coarsest_factorization_flops() +
                                             27 * coarse_blocks);
  // solve: one more iteration adds one fine product, one V-cycle and 15 vector passes; a V-cycle
  // reads the fine matrix one and a half times at least (the post-smoothing sweep, and the sweep
  // from zero, which reads the blocks below the diagonal and forms the residual from them).
  const auto t6 = step_traffic(problem, solver, 2.0, 6.0);
  const double fine_matrix = 76 * blocks + 4 * (v + 1);
  const double per_iteration = t6.at("solve").bytes - t.at("solve").bytes;
  // At most: the smoother's inverse diagonal and row data, the transfers and vectors (under 200 B
  // a DOF on a lattice of 8 weights a vertex) and the coarsest substitutions (L read twice).
  const double coarsest =
      16 * solver.coarsest_factor_nonzeros() + 32 * 3.0 * h.matrix(1).block_rows;
  EXPECT_LE(per_iteration, 4 * fine_matrix + 15 * 8 * n + 3 * (72 + 4) * v + 200 * n + coarsest);
  EXPECT_GE(per_iteration, 2.5 * fine_matrix + 15 * 8 * n + 16 * solver.coarsest_factor_nonzeros());
  // rotate's flops grow by 250 per tet per Newton iteration.
  const auto t3 = step_traffic(problem, solver, 3.0, 5.0);
  EXPECT_DOUBLE_EQ(t3.at("rotate").flops - t.at("rotate").flops, 250 * e);
  // With two levels the update overlaps nothing at two threads either (MultigridSolver::
  // overlaps_update): the same traffic, phase by phase.
  const ScopedThreadCount two(2);
  ASSERT_FALSE(solver.defers_update());
  const auto t2 = step_traffic(problem, solver, 2.0, 5.0);
  for (const char* phase : {"update", "solve"}) {
    EXPECT_DOUBLE_EQ(t2.at(phase).bytes, t.at(phase).bytes) << phase;
    EXPECT_DOUBLE_EQ(t2.at(phase).flops, t.at(phase).flops) << phase;
  }
}

TEST(StepRoofline, ADeferredUpdateMovesItsTrafficToTheSolve) {
  // At two threads and three levels MG-PCG factors the coarsest level and sets up the smoothers
  // in the solve (MultigridSolver::defers_update): their traffic moves with them, the step's
  // total stays.
  nlohmann::json scene = box_scene();
  scene["analysis"]["levels"] = 3;
  const ScopedThreadCount one(1);
  SceneSimulation sim(parse_scene(scene, ".", "box"));
  sim.run();
  const auto& solver = dynamic_cast<const MultigridSolver&>(sim.solver());
  const MultigridHierarchy& h = solver.hierarchy();
  ASSERT_EQ(h.num_levels(), 3);
  const auto t = step_traffic(sim.problem(), solver, 2.0, 5.0);
  const ScopedThreadCount two(2);
  ASSERT_TRUE(solver.defers_update());
  const auto t2 = step_traffic(sim.problem(), solver, 2.0, 5.0);
  // The smoothers' set-up: 50 flops a vertex on each level but the coarsest.
  const double moved = solver.coarsest_factorization_flops() +
                       50.0 * (h.matrix(0).block_rows + h.matrix(1).block_rows);
  EXPECT_DOUBLE_EQ(t2.at("update").flops, t.at("update").flops - moved);
  EXPECT_DOUBLE_EQ(t2.at("solve").flops, t.at("solve").flops + moved);
  EXPECT_DOUBLE_EQ(t2.at("update").bytes + t2.at("solve").bytes,
                   t.at("update").bytes + t.at("solve").bytes);
}

TEST(StepRoofline, TheCoarsestPartCountsOnlyTheUpdatesThatRefactor) {
  // A coarsest factor kept while its operator barely moves (analysis.coarsest_refactor): each
  // update is charged its share of the factorizations, and every update the check that decided
  // (3 flops a value of the coarsest level). At 0 all 4 updates refactor; at 1 (a move of 100%)
  // only the first does.
  for (const double refactor : {0.0, 1.0}) {
    nlohmann::json scene = box_scene();
    scene["analysis"]["steps"] = 4;
    scene["analysis"]["coarsest_refactor"] = refactor;
    const ScopedThreadCount one(1);
    SceneSimulation sim(parse_scene(scene, ".", "box"));
    sim.run();
    const auto& solver = dynamic_cast<const MultigridSolver&>(sim.solver());
    const MultigridHierarchy& h = solver.hierarchy();
    const MultigridSummary summary = *sim.multigrid_summary(sim.solver());
    ASSERT_EQ(summary.updates, 4) << refactor;
    const int factorizations = refactor == 0 ? 4 : 1;
    ASSERT_EQ(summary.coarsest_factorizations, factorizations) << refactor;
    const double values = static_cast<double>(h.matrix(h.num_levels() - 1).values.size());
    EXPECT_DOUBLE_EQ(update_traffic(solver, summary.refactor_share()).at("coarsest").flops,
                     factorizations / 4.0 * solver.coarsest_factorization_flops() + 3 * values)
        << refactor;
  }
}

TEST(StepRoofline, ChebyshevSmoothingCountsItsOwnProducts) {
  // The smoother counts its own traffic (linalg/smoother.hpp): Chebyshev of degree 3 reads the
  // fine matrix three times a smoothing (from x = 0: twice, and the V-cycle's residual once
  // more), so an iteration reads it 2 x 3 + 1 times with CG's product; Gauss-Seidel's sweeps read
  // it about 2.5 times, which the roofline once counted for every smoother.
  nlohmann::json scene = box_scene();
  scene["analysis"]["smoother"] = "chebyshev";
  scene["analysis"]["chebyshev_degree"] = 3;
  SceneSimulation sim(parse_scene(scene, ".", "box"));
  sim.run();
  const auto& solver = dynamic_cast<const MultigridSolver&>(sim.solver());
  EXPECT_EQ(solver.smoother(0).describe().text("kind"), "chebyshev");
  const FeProblem& problem = sim.problem();
  const double v = problem.mesh.num_vertices(), n = 3 * v;
  const double blocks = static_cast<double>(problem.stiffness.col_index.size());
  const double fine_matrix = 76 * blocks + 4 * (v + 1);
  const double per_iteration = step_traffic(problem, solver, 2.0, 6.0).at("solve").bytes -
                               step_traffic(problem, solver, 2.0, 5.0).at("solve").bytes;
  const MultigridHierarchy& h = solver.hierarchy();
  const double coarsest =
      16 * solver.coarsest_factor_nonzeros() + 32 * 3.0 * h.matrix(1).block_rows;
  EXPECT_GE(per_iteration, 7 * fine_matrix + 15 * 8 * n + 16 * solver.coarsest_factor_nonzeros());
  // At most: besides, each of the 6 Chebyshev steps' inverse diagonal and 8 vector passes, the
  // transfers (under 200 B a DOF); two levels, so no coarse level smooths.
  EXPECT_LE(per_iteration,
            7 * fine_matrix + 15 * 8 * n + 6 * (72 * v + 64 * n) + 200 * n + coarsest);
}

TEST(StepRoofline, RecordComparesEachPhaseWithItsFloor) {
  const std::map<std::string, Traffic> traffic = {{"rotate", {2e9, 1e9}}, {"solve", {1e9, 4e10}}};
  const auto record = roofline_record(
      traffic, {{"rotate", 400.0}, {"solve", 50.0}, {"step", 500.0}}, {10.0, 200.0}, 3e8);
  // rotate: 2e9 B at 10 GB/s is 200 ms, 1e9 flop at 200 Gflop/s 5 ms: memory bound, 200 ms.
  EXPECT_DOUBLE_EQ(record["phases"]["rotate"]["floor_ms"].get<double>(), 200.0);
  EXPECT_EQ(record["phases"]["rotate"]["bound"], "memory");
  EXPECT_DOUBLE_EQ(record["phases"]["rotate"]["over_floor"].get<double>(), 2.0);
  // solve: 100 ms of bytes, 200 ms of flops: compute bound.
  EXPECT_DOUBLE_EQ(record["phases"]["solve"]["floor_ms"].get<double>(), 200.0);
  EXPECT_EQ(record["phases"]["solve"]["bound"], "compute");
  EXPECT_DOUBLE_EQ(record["phases"]["solve"]["over_floor"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(record["phases"]["solve"]["flops_per_byte"].get<double>(), 40.0);
  EXPECT_DOUBLE_EQ(record["floor_ms"].get<double>(), 400.0);
  EXPECT_DOUBLE_EQ(record["over_floor"].get<double>(), 500.0 / 400.0);
}

}  // namespace
}  // namespace corofem
