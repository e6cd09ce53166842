// Every threaded kernel of a step at one thread and at thread_count() (--threads N) in the same
// run, alternated, medians of the repetitions: ms at both counts and the speedup. Issue 12's
// per-kernel target: energy-newton rotations <= 150 ns per element inside the step (counter
// rotate_ns_per_element at all threads; rotate_one_ns_per_element at one).
#include <benchmark/benchmark.h>

#include <chrono>
#include <functional>
#include <map>

#include "bench_support.hpp"
#include "core/statistics.hpp"
#include "core/threads.hpp"
#include "fem/corotated_assembly.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem::bench {
namespace {

void BM_ThreadScaling(benchmark::State& state, const std::string& model) {
  FeProblem& p = paper_problem(model);
  const Eigen::VectorXd u = bent_displacement(p);
  const std::vector<Vec3> x = p.positions(u);
  auto rotate = make_rotation_extractor(RotationMethod::EnergyNewton, p.mesh);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  rotate->extract(x, rotations);  // warm: the step's rotations start from the previous ones
  const std::vector<Mat3> warm = rotations;
  Eigen::VectorXd force, y;
  const PaperSystem& system = paper_system(model);
  MultigridParams params;
  params.hierarchy.levels = hierarchy_levels(model, HierarchyKind::Meshes);
  params.smoother = "domains";  // exact Gauss-Seidel inside the domains
  MultigridSolver solver(system.matrix, paper_transfers(model, HierarchyKind::Meshes), params,
                         true);
  solver.set_matrix(system.matrix);
  MultigridHierarchy hierarchy(system.matrix,
                               paper_transfers(model, HierarchyKind::Meshes).transfers);
  hierarchy.prepare(GalerkinMethod::Gather);
  Eigen::VectorXd vx = Eigen::VectorXd::Zero(system.rhs.size());
  const std::vector<std::pair<std::string, std::function<void()>>> kernels = {
      {"rotate",
       [&] {
         rotations = warm;
         rotate->extract(x, rotations);
       }},
      {"assemble",
       [&] {
         assemble_corotated(p.elements, p.mesh, p.assembly, rotations, u, p.stiffness, force);
       }},
      {"forces", [&] { force = internal_forces(p, rotations, u); }},  // Newton's residual pass
      {"spmv", [&] { system.matrix.multiply(system.rhs, y); }},
      {"galerkin", [&] { hierarchy.update(system.matrix, GalerkinMethod::Gather); }},
      {"vcycle", [&] { solver.vcycle(0, system.rhs, vx, true); }}};
  const int threads = thread_count();
  std::map<std::string, std::vector<double>> one, all;
  for (auto _ : state) {
    for (const auto& [name, run] : kernels) {
      {  // each warm from its own runs, not from the kernel before it (warm_time_ms)
        const ScopedThreadCount single(1);
        one[name].push_back(warm_time_ms(run));
      }
      all[name].push_back(warm_time_ms(run));
    }
  }
  for (const auto& [name, run] : kernels) {
    state.counters[name + "_one_ms"] = median(one[name]);
    state.counters[name + "_ms"] = median(all[name]);
    state.counters[name + "_speedup"] = median(one[name]) / median(all[name]);
  }
  state.counters["threads"] = threads;
  state.counters["rotate_ns_per_element"] = 1e6 * median(all["rotate"]) / p.mesh.num_tets();
  state.counters["rotate_one_ns_per_element"] = 1e6 * median(one["rotate"]) / p.mesh.num_tets();
}

BENCHMARK_CAPTURE(BM_ThreadScaling, bunny, std::string("bunny"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_ThreadScaling, horse, std::string("horse"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_ThreadScaling, dragon, std::string("dragon"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);

}  // namespace
}  // namespace corofem::bench
