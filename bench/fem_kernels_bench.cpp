// Kernels of one corotated step on paper-sized meshes: assembly through stored block indices
// (paper 4.2) and BRC SpMV.
#include <benchmark/benchmark.h>

#include "bench_support.hpp"
#include "core/statistics.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/dirichlet.hpp"
#include "fem/rotation_tangent.hpp"
#include "integrate/implicit_euler.hpp"
#include "integrate/newton_iteration.hpp"
#include "integrate/preconditioned_gmres_solve.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/solver_factory.hpp"

namespace corofem::bench {
namespace {

/// cold: the caches evicted before each pass (untimed), as in the step, where the Galerkin
/// stream has run since the last assembly.
void BM_CorotatedAssembly(benchmark::State& state, const std::string& model, bool cold) {
  FeProblem& p = paper_problem(model);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  const Eigen::VectorXd u = bent_displacement(p);
  polar->extract(p.positions(u), rotations);
  Eigen::VectorXd force;
  for (auto _ : state) {  // Ktilde and the elastic force, in one pass
    if (cold) {
      state.PauseTiming();
      evict_caches();
      state.ResumeTiming();
    }
    assemble_corotated(p.elements, p.mesh, p.assembly, rotations, u, p.stiffness, force);
    benchmark::DoNotOptimize(p.stiffness.values.data());
  }
  const double blocks = 16.0 * p.mesh.num_tets();
  state.counters["tets"] = p.mesh.num_tets();
  state.counters["blocks_per_s"] =
      benchmark::Counter(blocks, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_BrcSpmv(benchmark::State& state, const std::string& model) {
  FeProblem& p = paper_problem(model);
  std::vector<Mat3> identity(p.mesh.tets.size(), Mat3::Identity());
  Eigen::VectorXd force;
  assemble_corotated(p.elements, p.mesh, p.assembly, identity, Eigen::VectorXd::Zero(p.num_dofs()),
                     p.stiffness, force);
  Eigen::VectorXd x = Eigen::VectorXd::Random(p.num_dofs()), y;
  for (auto _ : state) {
    p.stiffness.multiply(x, y);
    benchmark::DoNotOptimize(y.data());
  }
  // Compulsory traffic: 72 B of values + 4 B column index per block, row offsets, x read once,
  // y written once.
  const double nb = p.stiffness.num_blocks(), nv = p.stiffness.block_rows;
  const double bytes = 76 * nb + 4 * (nv + 1) + 2 * 24 * nv;
  state.counters["blocks"] = nb;
  state.counters["bytes_per_spmv"] = bytes;
  state.counters["GB_per_s"] =
      benchmark::Counter(bytes / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

/// A Newton Euler step's tangent solve, M + dt^2 K_t with the energy rotations' (non-symmetric)
/// tangent of a cube of 7^3 vertices (the stability study's squashed block) squashed to 70% of
/// its height: GMRES on the symmetric part's Cholesky factor against UMFPACK's LU, alternated in
/// one run (medians; the ratio is the one to quote).
void BM_NewtonTangentSolve(benchmark::State& state) {
  TetMesh mesh = make_box_mesh({0.5, 0.5, 0.5}, {6, 6, 6});
  std::vector<Material> materials(mesh.tets.size(), Material{1e5, 0.3, 1000});
  FeProblem p = make_fe_problem(std::move(mesh), std::move(materials));
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v].z() < 1e-9) p.dirichlet.fix_vertex(v);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(p.num_dofs());
  for (int v = 0; v < p.mesh.num_vertices(); ++v) {  // squashed, and sheared a little
    const Vec3 x = p.mesh.rest[v];
    u.segment<3>(3 * v) = Vec3(0.2 * x.z() * x.z(), 0, -0.3 * x.z());
  }
  const std::vector<Vec3> positions = p.positions(u);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh)->extract(positions, rotations);
  BrcMatrix a = p.stiffness;
  RotationTangent(p, RotationMethod::EnergyNewton).assemble(positions, rotations, a);
  euler_newton_matrix(p, 0.01, 0, 1, a);  // M + dt^2 K_t at dt = 0.01
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.num_dofs(), -1, 1);
  apply_dirichlet(p.dirichlet, a, b);
  SparseLuSolve krylov(a), lu(a);
  lu.set_krylov(false);
  krylov.solve(a, b);  // the analyses, once per pattern
  lu.solve(a, b);
  std::vector<double> krylov_ms, lu_ms;
  for (auto _ : state) {
    krylov_ms.push_back(time_ms([&] { benchmark::DoNotOptimize(krylov.solve(a, b).data()); }));
    lu_ms.push_back(time_ms([&] { benchmark::DoNotOptimize(lu.solve(a, b).data()); }));
  }
  state.counters["dofs"] = p.num_dofs();
  state.counters["krylov_ms"] = median(krylov_ms);
  state.counters["lu_ms"] = median(lu_ms);
  state.counters["krylov_over_lu"] = median(krylov_ms) / median(lu_ms);
  state.counters["krylov_solves"] = krylov.krylov_solves();
  state.counters["lu_fallbacks"] = krylov.lu_solves();
}

/// Static Newton's tangent at the scale a factorization struggles with: the energy rotations'
/// (non-symmetric) tangent K_t of a 1 x 0.2 x 0.2 m bar fixed at one end and bent down by a tip
/// load (0.1 m at its tip), 6 x (5k) x k x k tets: the sparse factorizations (GMRES on the
/// symmetric part's Cholesky factor, or the LU) against GMRES on MG-PCG to 1e-2 (the bar's
/// re-meshed coarse levels, as a scene's `solver: mgpcg` gets them), both to 1e-12 of the residual,
/// alternated in one run (medians; the ratio is the one to quote). The first solve of each, the
/// analyses, is not timed. The second argument compresses the bent bar along its axis by that many
/// percent: at 0 the tangent's symmetric part is definite (the state is near the corotated
/// equilibrium); at 5 it is not, so the factorizations take the LU and the multigrid the definite
/// stand-in, the corotated stiffness (`gmres_standin_fallbacks`, per solve).
void BM_StaticTangentSolve(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const double compression = 0.01 * static_cast<double>(state.range(1));
  MeshSpec spec;
  spec.kind = MeshSpec::Kind::Box;
  spec.box = Vec3(1.0, 0.2, 0.2);
  spec.cells = {5 * k, k, k};
  TetMesh mesh = make_box_mesh(spec.box, spec.cells);
  std::vector<Material> materials(mesh.tets.size(), Material{5e6, 0.3, 1000});
  FeProblem p = make_fe_problem(std::move(mesh), std::move(materials));
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v].x() < 1e-9) p.dirichlet.fix_vertex(v);
  // The small-strain answer to a load down on the tip face, scaled to a 0.1 m tip deflection: a
  // state near the corotated equilibrium (a bent shape imposed without it stretched the bar's
  // fibres, and the tangent's symmetric part was no longer definite).
  Eigen::VectorXd u = Eigen::VectorXd::Zero(p.num_dofs());
  {
    std::vector<Mat3> identity(p.mesh.tets.size(), Mat3::Identity());
    Eigen::VectorXd force, f = Eigen::VectorXd::Zero(p.num_dofs());
    assemble_corotated(p.elements, p.mesh, p.assembly, identity, u, p.stiffness, force);
    for (int v = 0; v < p.mesh.num_vertices(); ++v)
      if (p.mesh.rest[v].x() > 1 - 1e-9) f[3 * v + 2] = -1;
    BrcMatrix k = p.stiffness;
    apply_dirichlet(p.dirichlet, k, f);
    auto cholmod = make_cholmod_solver();
    cholmod->set_matrix(k);
    cholmod->solve(f, u);
    u *= 0.1 / u.cwiseAbs().maxCoeff();
    for (int v = 0; v < p.mesh.num_vertices(); ++v) u[3 * v] -= compression * p.mesh.rest[v].x();
  }
  const std::vector<Vec3> positions = p.positions(u);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh)->extract(positions, rotations);
  BrcMatrix a = p.stiffness;
  RotationTangent(p, RotationMethod::EnergyNewton).assemble(positions, rotations, a);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.num_dofs(), -1, 1);
  apply_dirichlet(p.dirichlet, a, b);
  AnalysisSpec analysis;
  analysis.solver = SolverKind::Mgpcg;
  analysis.multigrid.hierarchy.kind = HierarchyKind::Meshes;
  analysis.multigrid.hierarchy.levels = 3;
  analysis.tolerance = kTangentPreconditionerTolerance;
  auto mg = make_multigrid_solver(
      analysis, p,
      coarse_meshes(spec, analysis.multigrid.hierarchy.levels, "bar", p.mesh.num_vertices()), true);
  SparseLuSolve factored(a);
  PreconditionedGmresSolve gmres(*mg, a, 1e-10, corotated_stiffness_standin(p, rotations));
  factored.solve(a, b);
  gmres.solve(a, b, false);
  const int gmres_before = gmres.iterations();
  std::vector<double> factored_ms, gmres_ms;
  Eigen::VectorXd x, y;
  for (auto _ : state) {
    factored_ms.push_back(time_ms([&] { x = factored.solve(a, b); }));
    gmres_ms.push_back(time_ms([&] { y = gmres.solve(a, b, false); }));
  }
  state.counters["tets"] = p.mesh.num_tets();
  state.counters["factored_ms"] = median(factored_ms);
  state.counters["gmres_ms"] = median(gmres_ms);
  state.counters["gmres_over_factored"] = median(gmres_ms) / median(factored_ms);
  state.counters["gmres_iterations"] =
      static_cast<double>(gmres.iterations() - gmres_before) / factored_ms.size();
  const double solves = static_cast<double>(factored_ms.size() + 1);  // with the untimed first
  state.counters["gmres_factored_fallbacks"] = gmres.fallbacks().factored / solves;
  state.counters["gmres_standin_fallbacks"] = gmres.fallbacks().standin / solves;
  state.counters["levels"] = mg->hierarchy().num_levels();
  state.counters["difference"] = (x - y).norm() / x.norm();
}

BENCHMARK_CAPTURE(BM_CorotatedAssembly, bunny, std::string("bunny"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CorotatedAssembly, horse, std::string("horse"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CorotatedAssembly, dragon, std::string("dragon"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CorotatedAssembly, dragon_cold, std::string("dragon"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BrcSpmv, bunny, std::string("bunny"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BrcSpmv, horse, std::string("horse"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BrcSpmv, dragon, std::string("dragon"))->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonTangentSolve)->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK(BM_StaticTangentSolve)
    ->Args({8, 0})
    ->Args({12, 0})
    ->Args({8, 5})
    ->Args({12, 5})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

}  // namespace
}  // namespace corofem::bench
