// Kernels of one corotated step on paper-sized meshes: assembly through stored block indices
// (paper 4.2) and BRC SpMV.
#include <benchmark/benchmark.h>

#include "bench_support.hpp"
#include "fem/corotated_assembly.hpp"
#include "rotation/rotation_extractor.hpp"

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

}  // namespace
}  // namespace corofem::bench
