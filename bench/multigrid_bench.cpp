// The Galerkin update of the whole hierarchy (every coarse level, E = R A R^T) by the paper's
// naive eq. (9), its stream (Algorithm 1), the pattern-reuse triple product and Eigen's sparse
// product; the same-run ratios; the stream's memory, bytes per update and effective bandwidth
// against a STREAM triad measured in this binary; one V-cycle; an MG-PCG solve to 1e-6; the
// multigrid quality of both hierarchies against Jacobi-PCG (issue 11).
// Targets (issue 4): stream >= 10x naive (paper 9.8x, 9.1x, 12.6x), >= 2x reuse, >= 3x eigen.
#include <benchmark/benchmark.h>

#include <chrono>

#include "bench_support.hpp"
#include "core/machine_roofs.hpp"
#include "core/statistics.hpp"
#include "core/threads.hpp"
#include "element/material.hpp"
#include "fem/corotated_assembly.hpp"
#include "fem/dirichlet.hpp"
#include "galerkin_oracle.hpp"
#include "linalg/gauss_seidel.hpp"
#include "linalg/gauss_seidel_smoother.hpp"
#include "linalg/preconditioned_cg.hpp"
#include "mesh/box_mesh.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "multigrid/multigrid_summary.hpp"
#include "single_precision_kernels.hpp"
#include "solver/petsc_galerkin.hpp"
#include "solver/petsc_solver.hpp"
#include "sparse/block_kernels.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem::bench {
namespace {

/// The Galerkin benchmarks run on the paper's kind of hierarchy (coarser meshes of the body).
MultigridHierarchy& paper_hierarchy(const std::string& model) {
  static std::map<std::string, std::unique_ptr<MultigridHierarchy>> cache;
  auto& slot = cache[model];
  if (!slot) {
    slot = std::make_unique<MultigridHierarchy>(
        paper_system(model).matrix, paper_transfers(model, HierarchyKind::Meshes).transfers);
    // Every method's streams before any timing (they are built on first use otherwise).
    for (const GalerkinMethod m :
         {GalerkinMethod::Stream, GalerkinMethod::StreamFull, GalerkinMethod::Gather})
      slot->prepare(m);
  }
  return *slot;
}

/// Eigen's R A R^T on every level, pattern computed afresh each time (what a generic sparse
/// library does); the conversions of A are part of the cost.
void eigen_update(MultigridHierarchy& h, const std::vector<Eigen::SparseMatrix<double>>& r) {
  Eigen::SparseMatrix<double> a = to_eigen(h.matrix(0));
  for (int l = 0; l + 1 < h.num_levels(); ++l) {
    a = reference::eigen_galerkin(r[l], a);
    benchmark::DoNotOptimize(a.valuePtr());
  }
}

/// Compulsory traffic of one stream update: the streams, A's blocks of every level read once,
/// E's blocks written once.
double stream_update_bytes(const MultigridHierarchy& h, GalerkinMethod format) {
  double bytes = static_cast<double>(h.stream_bytes(format));
  for (int l = 0; l < h.num_levels(); ++l)
    bytes += 72.0 * h.matrix(l).num_blocks() * (l == 0 || l + 1 == h.num_levels() ? 1 : 2);
  return bytes;
}

void BM_GalerkinUpdate(benchmark::State& state, const std::string& method,
                       const std::string& model) {
  MultigridHierarchy& h = paper_hierarchy(model);
  const BrcMatrix& a = paper_system(model).matrix;
  std::vector<Eigen::SparseMatrix<double>> r;
  for (int l = 0; l + 1 < h.num_levels(); ++l) r.push_back(restriction_matrix(h.transfer(l)));
  std::unique_ptr<PetscPtapHierarchy> petsc;
  if (method == "petsc-ptap") {
    if (!have_petsc()) {
      state.SkipWithError("this build has no PETSc");
      return;
    }
    petsc = std::make_unique<PetscPtapHierarchy>(
        a, paper_transfers(model, HierarchyKind::Meshes).transfers);
    petsc->update(a);  // symbolic phase: once, outside the timing (numeric reuse is timed)
  }
  for (auto _ : state) {
    if (method == "eigen")
      eigen_update(h, r);
    else if (petsc)
      petsc->update(a);
    else
      h.update(a, *kGalerkinMethods.find(method));
    benchmark::ClobberMemory();
  }
  state.counters["levels"] = h.num_levels();
  state.counters["fine_blocks"] = a.num_blocks();
  if (method == "stream" || method == "stream-full" || method == "gather") {
    const double bytes = stream_update_bytes(h, *kGalerkinMethods.find(method));
    state.counters["stream_MB"] = h.stream_bytes(*kGalerkinMethods.find(method)) / 1e6;
    state.counters["bytes_per_update"] = bytes;
    state.counters["GB_per_s"] =
        benchmark::Counter(bytes / 1e9, benchmark::Counter::kIsIterationInvariantRate);
  }
}

/// The four methods timed alternately in one run: ratios immune to the machine's drift.
void BM_GalerkinRatio(benchmark::State& state, const std::string& model) {
  MultigridHierarchy& h = paper_hierarchy(model);
  const BrcMatrix& a = paper_system(model).matrix;
  std::vector<Eigen::SparseMatrix<double>> r;
  for (int l = 0; l + 1 < h.num_levels(); ++l) r.push_back(restriction_matrix(h.transfer(l)));
  double t[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // ms
  std::unique_ptr<PetscPtapHierarchy> petsc;  // PETSc's MatPtAP in numeric-reuse mode
  if (have_petsc()) {
    petsc = std::make_unique<PetscPtapHierarchy>(
        a, paper_transfers(model, HierarchyKind::Meshes).transfers);
    petsc->update(a);
  }
  // Each timed update follows untimed ones of the same method (warm_time_ms): timed right after
  // the full stream, the gather ran at 0.77x the stream on the dragon.
  for (auto _ : state) {
    t[0] += warm_time_ms([&] { h.update(a, GalerkinMethod::Naive); });
    t[1] += warm_time_ms([&] { h.update(a, GalerkinMethod::Stream); });
    t[2] += warm_time_ms([&] { h.update(a, GalerkinMethod::Reuse); });
    t[3] += warm_time_ms([&] { eigen_update(h, r); });
    t[4] += warm_time_ms([&] { h.update(a, GalerkinMethod::StreamFull); });
    t[8] += warm_time_ms([&] { h.update(a, GalerkinMethod::Gather); });
    if (petsc) t[5] += warm_time_ms([&] { petsc->update(a); });
    // Stream and reuse share their scatter kernel; again in its scalar form (the portable one,
    // sparse/block_kernels.hpp): the ratio of the algorithms in both.
    const bool vector = set_vector_block_kernels(false);
    t[6] += warm_time_ms([&] { h.update(a, GalerkinMethod::Stream); });
    t[7] += warm_time_ms([&] { h.update(a, GalerkinMethod::Reuse); });
    set_vector_block_kernels(vector);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["naive_ms"] = t[0] / n;
  state.counters["stream_ms"] = t[1] / n;
  state.counters["reuse_ms"] = t[2] / n;
  state.counters["eigen_ms"] = t[3] / n;
  state.counters["naive_over_stream"] = t[0] / t[1];
  state.counters["reuse_over_stream"] = t[2] / t[1];
  state.counters["eigen_over_stream"] = t[3] / t[1];
  state.counters["stream_full_ms"] = t[4] / n;
  state.counters["naive_over_stream_full"] = t[0] / t[4];
  state.counters["reuse_over_stream_full"] = t[2] / t[4];
  // The stream's pairs by destination (the default), against the stream and reuse.
  state.counters["gather_ms"] = t[8] / n;
  state.counters["stream_over_gather"] = t[1] / t[8];
  state.counters["reuse_over_gather"] = t[2] / t[8];
  state.counters["stream_scalar_ms"] = t[6] / n;
  state.counters["reuse_scalar_ms"] = t[7] / n;
  state.counters["reuse_over_stream_scalar"] = t[7] / t[6];
  if (petsc) {  // issue 14's target: stream >= 2x MatPtAP numeric reuse
    state.counters["petsc_ptap_ms"] = t[5] / n;
    state.counters["petsc_ptap_over_stream"] = t[5] / t[1];
  }
}

/// The symmetric stream and the gather level by level, alternated in one run, each warm from its
/// own runs (medians): where each wins, against the level's pairs per block of A (the gather
/// reads A once per pair, out of order; the stream reads A once, in order, and adds into E pair
/// by pair).
void BM_GalerkinLevels(benchmark::State& state, const std::string& model) {
  MultigridHierarchy& h = paper_hierarchy(model);
  h.update(paper_system(model).matrix, GalerkinMethod::Gather);
  const int levels = h.num_levels() - 1;
  std::vector<std::vector<double>> stream_ms(levels), gather_ms(levels);
  for (auto _ : state)
    for (int l = 0; l < levels; ++l) {
      stream_ms[l].push_back(
          warm_time_ms([&] { h.stream(l).apply(h.matrix(l), h.matrix(l + 1)); }));
      gather_ms[l].push_back(
          warm_time_ms([&] { h.gather(l).apply(h.matrix(l), h.matrix(l + 1)); }));
    }
  for (int l = 0; l < levels; ++l) {
    const std::string level = "L" + std::to_string(l);
    state.counters[level + "_pairs_per_A_block"] =
        static_cast<double>(h.gather(l).num_pairs()) / h.matrix(l).num_blocks();
    state.counters[level + "_stream_ms"] = median(stream_ms[l]);
    state.counters[level + "_gather_ms"] = median(gather_ms[l]);
    state.counters[level + "_stream_over_gather"] = median(stream_ms[l]) / median(gather_ms[l]);
  }
  state.counters["threads"] = thread_count();
}

/// STREAM triad a = b + s c on arrays far larger than the caches: the machine's bandwidth.
void BM_StreamTriad(benchmark::State& state) {
  const std::size_t n = 1 << 24;  // 3 x 128 MiB
  std::vector<double> a(n, 0), b(n, 1), c(n, 2);
  const double s = 3;
  for (auto _ : state) {
    stream_triad(a.data(), b.data(), c.data(), s, n);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["GB_per_s"] =
      benchmark::Counter(24.0 * n / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

MultigridSolver& paper_solver(const std::string& model, bool pcg,
                              HierarchyKind kind = HierarchyKind::Meshes) {
  static std::map<std::string, std::unique_ptr<MultigridSolver>> cache;
  auto& slot = cache[model + (pcg ? "/pcg/" : "/") + kHierarchyKinds.name(kind)];
  if (!slot) {
    MultigridParams params;
    params.hierarchy.kind = kind;
    params.hierarchy.levels = hierarchy_levels(model, kind);
    params.tolerance = 1e-6;
    slot = std::make_unique<MultigridSolver>(paper_system(model).matrix,
                                             paper_transfers(model, kind), params, pcg);
    slot->set_matrix(paper_system(model).matrix);
  }
  return *slot;
}

void BM_VCycle(benchmark::State& state, const std::string& model) {
  MultigridSolver& solver = paper_solver(model, false);
  const Eigen::VectorXd& b = paper_system(model).rhs;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  for (auto _ : state) {
    x.setZero();
    solver.vcycle(0, b, x, true);
    benchmark::DoNotOptimize(x.data());
  }
}

void BM_MgpcgSolve(benchmark::State& state, const std::string& model) {
  MultigridSolver& solver = paper_solver(model, true);
  const Eigen::VectorXd& b = paper_system(model).rhs;
  Eigen::VectorXd x;
  SolveStats stats;
  for (auto _ : state) {
    x = Eigen::VectorXd::Zero(b.size());
    stats = solver.solve(b, x);
  }
  state.counters["iterations"] = stats.iterations;
  state.counters["residual"] = stats.residual;
  state.counters["rho"] = stats.convergence_factor;
}

/// What a dynamic step of the report solves: A = M + dt^2 K (dt = 0.01 s) with paper_system's
/// stiffness and supports (their rows stay dt^2 I). Cached per model.
const PaperSystem& step_system(const std::string& model) {
  static std::map<std::string, PaperSystem> cache;
  if (auto it = cache.find(model); it != cache.end()) return it->second;
  PaperSystem s = paper_system(model);
  const FeProblem& p = paper_problem(model);
  const double dt2 = 1e-4;
  for (double& value : s.matrix.values) value *= dt2;
  s.rhs *= dt2;
  for (int v = 0; v < s.matrix.block_rows; ++v) {
    if (s.fixed[v]) continue;
    auto block = s.matrix.block(s.matrix.find(v, v));
    for (int c = 0; c < 3; ++c) block(c, c) += p.mass[3 * v + c];
  }
  return cache[model] = std::move(s);
}

/// A step's update and solve, MG-PCG to 1e-4 from x = 0 on the step's matrix, with the coarsest
/// factorization in the update or overlapped with the solve's start (the default at two or more
/// threads), alternated in one run (medians). The two give the same bits.
void BM_UpdateSolveOverlap(benchmark::State& state, const std::string& model) {
  const PaperSystem& system = step_system(model);
  MultigridParams params;
  params.hierarchy.levels = hierarchy_levels(model, HierarchyKind::Meshes);
  params.tolerance = 1e-4;
  params.smoother = "hybrid";
  std::vector<std::unique_ptr<MultigridSolver>> solvers;
  for (const bool overlap : {false, true}) {
    params.overlap_factorization = overlap;
    solvers.push_back(std::make_unique<MultigridSolver>(
        system.matrix, paper_transfers(model, HierarchyKind::Meshes), params, true));
    solvers.back()->set_matrix(system.matrix);  // the first update analyses the pattern
  }
  std::vector<double> ms[2];
  Eigen::VectorXd x[2];
  for (auto _ : state)
    for (int k = 0; k < 2; ++k)
      ms[k].push_back(warm_time_ms([&] {
        solvers[k]->set_matrix(system.matrix);
        x[k].setZero(system.rhs.size());
        solvers[k]->solve(system.rhs, x[k]);
      }));
  if (x[0] != x[1]) state.SkipWithError("the overlapped solve gave other bits");
  state.counters["in_update_ms"] = median(ms[0]);
  state.counters["overlapped_ms"] = median(ms[1]);
  state.counters["in_update_over_overlapped"] = median(ms[0]) / median(ms[1]);
  state.counters["threads"] = thread_count();
}

/// One Gauss-Seidel sweep of the fine level (the mean of a forward and a backward one) in each
/// ordering against one product with the same matrix, alternated in one run: a sweep reads
/// what a product reads (every block once, x, b), so sweep / product near 1 is its floor.
void BM_SmootherSweep(benchmark::State& state, const std::string& model) {
  const PaperSystem& system = step_system(model);
  const BrcMatrix& a = system.matrix;
  const SmootherOrdering orderings[] = {SmootherOrdering::Sequential, SmootherOrdering::Multicolour,
                                        SmootherOrdering::Domains, SmootherOrdering::Hybrid};
  std::vector<BlockGaussSeidel> smoothers;
  for (const SmootherOrdering o : orderings) {
    smoothers.emplace_back(o);
    smoothers.back().set_matrix(a);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.rhs.size()), y;
  std::vector<std::vector<double>> sweep_ms(smoothers.size());
  std::vector<double> product_ms, from_zero_ms;
  for (auto _ : state) {
    product_ms.push_back(warm_time_ms([&] { a.multiply(system.rhs, y); }));
    from_zero_ms.push_back(
        warm_time_ms([&] { smoothers.back().forward_from_zero(a, system.rhs, y); }));
    for (std::size_t s = 0; s < smoothers.size(); ++s)
      sweep_ms[s].push_back(0.5 * warm_time_ms([&] {
                              smoothers[s].forward(a, system.rhs, x);
                              smoothers[s].backward(a, system.rhs, x);
                            }));
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["product_ms"] = median(product_ms);
  for (std::size_t s = 0; s < smoothers.size(); ++s) {
    const std::string name = kSmootherOrderings.name(orderings[s]);
    state.counters[name + "_sweep_ms"] = median(sweep_ms[s]);
    state.counters[name + "_over_product"] = median(sweep_ms[s]) / median(product_ms);
  }
  // A V-cycle's first sweep of a correction reads only the blocks below the diagonal.
  state.counters["hybrid_from_zero_ms"] = median(from_zero_ms);
  state.counters["hybrid_from_zero_over_product"] = median(from_zero_ms) / median(product_ms);
  state.counters["vertices"] = a.block_rows;
  state.counters["threads"] = thread_count();
}

/// The smoothers' set-up (issue 70: within 3x its floor) of every smoothed level of the paper's
/// hierarchy (the default hybrid smoother; the sequential one beside it), cold as in the step (the
/// Galerkin products have run since the assembly wrote the fine level's diagonal blocks) and
/// warm, against a pass with part of its compulsory traffic alone (every row's diagonal block
/// read, 72 bytes a row written), cold too, alternated in one run. floor_ms: the bytes the
/// roofline counts (Smoother::setup_traffic) over a STREAM triad of this run.
void BM_SmootherSetUp(benchmark::State& state, const std::string& model) {
  MultigridHierarchy& h = paper_hierarchy(model);
  h.update(paper_system(model).matrix, GalerkinMethod::Gather);
  const int smoothed = h.num_levels() - 1;
  std::vector<GaussSeidelSmoother> hybrid(smoothed, GaussSeidelSmoother(SmootherOrdering::Hybrid));
  std::vector<GaussSeidelSmoother> sequential(smoothed,
                                              GaussSeidelSmoother(SmootherOrdering::Sequential));
  std::vector<std::vector<int>> diagonal(smoothed);
  std::vector<std::vector<double>> copied(smoothed);
  Traffic traffic;
  for (int l = 0; l < smoothed; ++l) {
    const BrcMatrix& a = h.matrix(l);
    hybrid[l].set_matrix(a);
    sequential[l].set_matrix(a);
    traffic += hybrid[l].setup_traffic(a);
    for (int i = 0; i < a.block_rows; ++i) diagonal[l].push_back(a.find(i, i));
    copied[l].resize(9 * static_cast<std::size_t>(a.block_rows));
  }
  const auto set_up = [&](std::vector<GaussSeidelSmoother>& smoothers) {
    return [&] {
      for (int l = 0; l < smoothed; ++l) smoothers[l].set_matrix(h.matrix(l));
    };
  };
  const auto copy_diagonals = [&] {
    for (int l = 0; l < smoothed; ++l) {
      const BrcMatrix& a = h.matrix(l);
#pragma omp parallel for schedule(static) num_threads(threads_for(a.block_rows))
      for (int i = 0; i < a.block_rows; ++i)
        std::copy_n(a.values.data() + 9 * static_cast<std::size_t>(diagonal[l][i]), 9,
                    copied[l].data() + 9 * static_cast<std::size_t>(i));
    }
  };
  const auto cold_ms = [&](const std::function<void()>& f) {
    evict_caches();
    return time_ms(f);
  };
  std::vector<double> hybrid_cold, hybrid_warm, sequential_cold, sequential_warm, copy_cold;
  for (auto _ : state) {
    hybrid_cold.push_back(cold_ms(set_up(hybrid)));
    sequential_cold.push_back(cold_ms(set_up(sequential)));
    copy_cold.push_back(cold_ms(copy_diagonals));
    hybrid_warm.push_back(warm_time_ms(set_up(hybrid)));
    sequential_warm.push_back(warm_time_ms(set_up(sequential)));
    benchmark::DoNotOptimize(copied.data());
  }
  const double floor_ms = traffic.bytes / (measure_stream_triad_gbps() * 1e9) * 1e3;
  state.counters["hybrid_cold_ms"] = median(hybrid_cold);
  state.counters["hybrid_warm_ms"] = median(hybrid_warm);
  state.counters["sequential_cold_ms"] = median(sequential_cold);
  state.counters["sequential_warm_ms"] = median(sequential_warm);
  state.counters["copy_cold_ms"] = median(copy_cold);
  state.counters["floor_ms"] = floor_ms;
  state.counters["hybrid_cold_over_floor"] = median(hybrid_cold) / floor_ms;
  state.counters["hybrid_cold_over_copy"] = median(hybrid_cold) / median(copy_cold);
  state.counters["fine_rows"] = h.num_levels() > 1 ? h.matrix(0).block_rows : 0;
  state.counters["threads"] = thread_count();
}

/// The block passes in their AVX2 form against the scalar one (sparse/block_kernels.hpp),
/// alternated in one run: the product, and a hybrid forward plus backward sweep. And the
/// V-cycle's sweep from zero with its residual in one pass against the two passes it replaces.
void BM_BlockKernels(benchmark::State& state, const std::string& model) {
  const PaperSystem& system = step_system(model);
  const BrcMatrix& a = system.matrix;
  if (!set_vector_block_kernels(true)) {
    state.SkipWithError("this CPU has no AVX2/FMA: only the scalar form runs");
    return;
  }
  BlockGaussSeidel smoother(SmootherOrdering::Hybrid);
  smoother.set_matrix(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.rhs.size()), y;
  std::vector<double> product_ms[2], sweep_ms[2], descent_ms[2];
  Eigen::VectorXd z;
  // Issue 36's single-precision hierarchy: the same product and sweeps in float and double.
  const BlocksIn<double> blocks_double(a);
  const BlocksIn<float> blocks_float(a);
  const Eigen::VectorXf rhs_float = system.rhs.cast<float>();
  Eigen::VectorXf x_float = Eigen::VectorXf::Zero(rhs_float.size()), y_float(rhs_float.size());
  Eigen::VectorXd x_double = Eigen::VectorXd::Zero(system.rhs.size());
  Eigen::VectorXd y_double(system.rhs.size());
  Eigen::VectorXd x_mixed = Eigen::VectorXd::Zero(system.rhs.size());
  std::vector<double> product_double_ms, product_float_ms, sweeps_double_ms, sweeps_float_ms,
      sweeps_mixed_ms;
  for (auto _ : state) {
    product_double_ms.push_back(
        warm_time_ms([&] { multiply(blocks_double, system.rhs.data(), y_double.data()); }));
    product_float_ms.push_back(
        warm_time_ms([&] { multiply(blocks_float, rhs_float.data(), y_float.data()); }));
    sweeps_double_ms.push_back(
        warm_time_ms([&] { symmetric_sweeps(blocks_double, system.rhs.data(), x_double.data()); }));
    sweeps_float_ms.push_back(
        warm_time_ms([&] { symmetric_sweeps(blocks_float, rhs_float.data(), x_float.data()); }));
    sweeps_mixed_ms.push_back(
        warm_time_ms([&] { symmetric_sweeps(blocks_float, system.rhs.data(), x_mixed.data()); }));
    descent_ms[0].push_back(warm_time_ms([&] {
      smoother.forward_from_zero(a, system.rhs, z);
      a.residual(system.rhs, z, y);
    }));
    descent_ms[1].push_back(
        warm_time_ms([&] { smoother.forward_from_zero_with_residual(a, system.rhs, z, y); }));
    for (const bool vector : {false, true}) {
      set_vector_block_kernels(vector);
      product_ms[vector].push_back(warm_time_ms([&] { a.multiply(system.rhs, y); }));
      sweep_ms[vector].push_back(warm_time_ms([&] {
        smoother.forward(a, system.rhs, x);
        smoother.backward(a, system.rhs, x);
      }));
    }
    benchmark::DoNotOptimize(x.data());
  }
  set_vector_block_kernels(true);
  state.counters["product_scalar_ms"] = median(product_ms[0]);
  state.counters["product_avx2_ms"] = median(product_ms[1]);
  state.counters["product_speedup"] = median(product_ms[0]) / median(product_ms[1]);
  state.counters["sweeps_scalar_ms"] = median(sweep_ms[0]);
  state.counters["sweeps_avx2_ms"] = median(sweep_ms[1]);
  state.counters["sweeps_speedup"] = median(sweep_ms[0]) / median(sweep_ms[1]);
  state.counters["descent_separate_ms"] = median(descent_ms[0]);
  state.counters["descent_fused_ms"] = median(descent_ms[1]);
  state.counters["product_float_speedup"] = median(product_double_ms) / median(product_float_ms);
  state.counters["sweeps_float_speedup"] = median(sweeps_double_ms) / median(sweeps_float_ms);
  // the blocks in float, the vectors and sums in double: half the matrix's bytes only
  state.counters["sweeps_mixed_speedup"] = median(sweeps_double_ms) / median(sweeps_mixed_ms);
  // the float product's error against the double one, relative (float round-off: ~1e-7)
  state.counters["product_float_error"] =
      (y_float.cast<double>() - y_double).norm() / y_double.norm();
  state.counters["threads"] = thread_count();
}

/// Issue 11's targets in one run, for one model and hierarchy, on the dynamic step's matrix:
/// rho of V(1,1) (mean residual reduction over 12 stationary cycles from x = 0), MG-PCG and
/// Jacobi-PCG iterations to 1e-4, and their solve times in the same run (targets: rho <= 0.2,
/// MG-PCG <= 5 iterations, MG-PCG >= 2x faster than Jacobi-PCG).
void BM_MultigridQuality(benchmark::State& state, const std::string& model, HierarchyKind kind,
                         bool bare_surface = false) {
  const PaperSystem& system = step_system(model);
  MultigridParams params;
  params.hierarchy.kind = kind;
  params.hierarchy.levels = hierarchy_levels(model, kind);
  params.tolerance = 1e-4;
  BuiltHierarchy built = paper_transfers(model, kind, bare_surface);
  MultigridParams stationary = params;
  stationary.vcycles = 12;
  MultigridSolver vcycles(system.matrix, built, stationary, false),
      pcg(system.matrix, built, params, true);
  vcycles.set_matrix(system.matrix);
  pcg.set_matrix(system.matrix);
  auto jacobi = make_jacobi_pcg_solver(1e-4, 100000);
  jacobi->set_matrix(system.matrix);
  // The same hierarchy with the threaded Gauss-Seidel orderings and the other cycles (issue 36).
  struct Variant {
    std::string name;
    std::unique_ptr<MultigridSolver> vcycles, pcg;
    std::vector<double> ms;
    SolveStats rho, mg;
  };
  std::vector<std::pair<std::string, MultigridParams>> variants;
  for (const SmootherOrdering ordering :
       {SmootherOrdering::Multicolour, SmootherOrdering::Domains, SmootherOrdering::Hybrid}) {
    MultigridParams p = params;
    p.smoother = kSmootherOrderings.name(ordering);
    variants.emplace_back(kSmootherOrderings.name(ordering), p);
  }
  MultigridParams w_cycle = params, v22 = params;
  w_cycle.cycle = CycleShape::W;
  v22.pre_smoothing = v22.post_smoothing = 2;
  variants.emplace_back("w_cycle", w_cycle);
  variants.emplace_back("v22", v22);
  std::vector<Variant> ordered;
  for (const auto& [name, p] : variants) {
    MultigridParams s = p;
    s.vcycles = stationary.vcycles;
    Variant o{name,
              std::make_unique<MultigridSolver>(system.matrix, built, s, false),
              std::make_unique<MultigridSolver>(system.matrix, built, p, true),
              {},
              {},
              {}};
    o.vcycles->set_matrix(system.matrix);
    o.pcg->set_matrix(system.matrix);
    ordered.push_back(std::move(o));
  }
  std::vector<double> mg_ms, jacobi_ms;
  SolveStats rho, mg, jc;
  for (auto _ : state) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(system.rhs.size());
    rho = vcycles.solve(system.rhs, x);
    x.setZero();
    mg_ms.push_back(time_ms([&] { mg = pcg.solve(system.rhs, x); }));
    x.setZero();
    jacobi_ms.push_back(time_ms([&] { jc = jacobi->solve(system.rhs, x); }));
    for (Variant& o : ordered) {
      x.setZero();
      o.rho = o.vcycles->solve(system.rhs, x);
      x.setZero();
      o.ms.push_back(time_ms([&] { o.mg = o.pcg->solve(system.rhs, x); }));
    }
  }
  const MultigridSummary d = summarize(pcg, EventLog{});  // its levels: no log needed
  state.counters["rho"] = rho.convergence_factor;
  state.counters["mgpcg_iterations"] = mg.iterations;
  state.counters["jacobi_iterations"] = jc.iterations;
  state.counters["mgpcg_ms"] = median(mg_ms);
  state.counters["jacobi_ms"] = median(jacobi_ms);
  state.counters["jacobi_over_mgpcg"] = median(jacobi_ms) / median(mg_ms);
  for (const Variant& o : ordered) {
    state.counters["rho_" + o.name] = o.rho.convergence_factor;
    state.counters["mgpcg_iterations_" + o.name] = o.mg.iterations;
    state.counters["mgpcg_" + o.name + "_ms"] = median(o.ms);
  }
  state.counters["levels"] = params.hierarchy.levels;
  state.counters["operator_complexity"] = d.operator_complexity;
}

/// Issue 36's floor, on corofem's side: the two-grid cycle (coarse level solved exactly) on the
/// ideal hierarchy, the unit cube in N^3 Kuhn cells over the cube in (N/2)^3 (nested), clamped
/// at x = 0, E = 1, nu = 0.3, `mass_permille` / 1000 x the mean stiffness diagonal added as a
/// lumped mass. bench/nested_two_grid.py builds the same case with no corofem code: its
/// energy-norm factor and CG iterations are what `rho_<smoother>` and `mgpcg_iterations_<smoother>`
/// should give (rho here is the residual ratio of the last of 100 cycles on A e = 0).
void BM_NestedTwoGrid(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  const double mass_ratio = static_cast<double>(state.range(1)) / 1000;
  const TetMesh fine = make_box_mesh({1, 1, 1}, {cells, cells, cells});
  const TetMesh coarse = make_box_mesh({1, 1, 1}, {cells / 2, cells / 2, cells / 2});
  FeProblem problem = make_fe_problem(fine, materials_per_element(fine, Material{1, 0.3, 1}, {}));
  std::vector<char> fixed_vertices(fine.rest.size(), 0);
  for (int v = 0; v < fine.num_vertices(); ++v)
    if (fine.rest[v].x() < 1e-12) {
      problem.dirichlet.fix_vertex(v);
      fixed_vertices[v] = 1;
    }
  const std::vector<Mat3> identity(fine.tets.size(), Mat3::Identity());
  Eigen::VectorXd force;
  assemble_corotated(problem.elements, problem.mesh, problem.assembly, identity,
                     Eigen::VectorXd::Zero(problem.num_dofs()), problem.stiffness, force);
  BrcMatrix a = problem.stiffness;
  double diagonal = 0;
  int free_dofs = 0;
  for (int v = 0; v < fine.num_vertices(); ++v)
    if (!fixed_vertices[v]) {
      diagonal += a.block(problem.assembly.diagonal[v]).diagonal().sum();
      free_dofs += 3;
    }
  for (int v = 0; v < fine.num_vertices(); ++v)
    a.block(problem.assembly.diagonal[v]).diagonal().array() += mass_ratio * diagonal / free_dofs;
  Eigen::VectorXd load = Eigen::VectorXd::Zero(problem.num_dofs());
  for (int v = 0; v < fine.num_vertices(); ++v) load[3 * v + 2] = -1;  // a uniform body force
  apply_dirichlet(problem.dirichlet, a, load);
  HierarchyParams hierarchy;
  hierarchy.kind = HierarchyKind::Meshes;
  hierarchy.levels = 2;
  MultigridParams params;
  params.tolerance = 1e-4;
  params.smoother = "sequential";  // natural order, as the script's
  std::vector<std::pair<std::string, MultigridParams>> smoothers;
  for (int sweeps : {1, 2, 3}) {
    MultigridParams p = params;
    p.pre_smoothing = p.post_smoothing = sweeps;
    smoothers.emplace_back("gs" + std::to_string(sweeps), p);
  }
  for (int degree : {2, 3, 4}) {
    MultigridParams p = params;
    p.smoother = "chebyshev";
    p.smoother_parameters.set("chebyshev_degree", static_cast<long long>(degree));
    smoothers.emplace_back("chebyshev" + std::to_string(degree), p);
  }
  const BuiltHierarchy built = build_hierarchy(fine, fixed_vertices, hierarchy, {coarse});
  for (auto _ : state) {
    for (const auto& [name, p] : smoothers) {
      MultigridSolver cycle(a, built, p, false), pcg(a, built, p, true);
      cycle.set_matrix(a);
      pcg.set_matrix(a);
      Eigen::VectorXd e = Eigen::VectorXd::Random(a.block_rows * 3), r;
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(e.size());
      for (int d = 0; d < e.size(); ++d)
        if (problem.dirichlet.fixed[d]) e[d] = 0;
      double previous = 0, ratio = 0;
      for (int k = 0; k < 100; ++k) {
        cycle.vcycle(0, zero, e, false);
        a.multiply(e, r);
        ratio = previous > 0 ? r.norm() / previous : 0;
        previous = r.norm();
      }
      Eigen::VectorXd x = Eigen::VectorXd::Zero(load.size());
      state.counters["rho_" + name] = ratio;
      state.counters["mgpcg_iterations_" + name] = pcg.solve(load, x).iterations;
    }
  }
  state.counters["fine_dofs"] = 3 * fine.num_vertices();
}
BENCHMARK(BM_NestedTwoGrid)
    ->Args({4, 0})
    ->Args({16, 0})
    ->Args({16, 7})
    ->Args({16, 50})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

#define GALERKIN_CASES(model)                                                                      \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, naive / model, std::string("naive"), std::string(#model))   \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, stream / model, std::string("stream"), std::string(#model)) \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, stream_full / model, std::string("stream-full"),            \
                    std::string(#model))                                                           \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, reuse / model, std::string("reuse"), std::string(#model))   \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, gather / model, std::string("gather"), std::string(#model)) \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, eigen / model, std::string("eigen"), std::string(#model))   \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinUpdate, petsc_ptap / model, std::string("petsc-ptap"),              \
                    std::string(#model))                                                           \
      ->Unit(benchmark::kMillisecond);                                                             \
  BENCHMARK_CAPTURE(BM_GalerkinRatio, model, std::string(#model))                                  \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(10);                                                                            \
  BENCHMARK_CAPTURE(BM_GalerkinLevels, model, std::string(#model))                                 \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(5);                                                                             \
  BENCHMARK_CAPTURE(BM_VCycle, model, std::string(#model))->Unit(benchmark::kMillisecond);         \
  BENCHMARK_CAPTURE(BM_MgpcgSolve, model, std::string(#model))->Unit(benchmark::kMillisecond);     \
  BENCHMARK_CAPTURE(BM_SmootherSweep, model, std::string(#model))                                  \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(20);                                                                            \
  BENCHMARK_CAPTURE(BM_SmootherSetUp, model, std::string(#model))                                  \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(20);                                                                            \
  BENCHMARK_CAPTURE(BM_UpdateSolveOverlap, model, std::string(#model))                             \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(15);                                                                            \
  BENCHMARK_CAPTURE(BM_BlockKernels, model, std::string(#model))                                   \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->Iterations(20)

#define QUALITY_CASES(model)                                                        \
  BENCHMARK_CAPTURE(BM_MultigridQuality, model / meshes, std::string(#model),       \
                    HierarchyKind::Meshes)                                          \
      ->Unit(benchmark::kMillisecond)                                               \
      ->Iterations(3);                                                              \
  BENCHMARK_CAPTURE(BM_MultigridQuality, model / lattice, std::string(#model),      \
                    HierarchyKind::Lattice)                                         \
      ->Unit(benchmark::kMillisecond)                                               \
      ->Iterations(3);                                                              \
  /* issue 36: the levels derived from the fine surface alone, as a bare STL */     \
  BENCHMARK_CAPTURE(BM_MultigridQuality, model / bare_surface, std::string(#model), \
                    HierarchyKind::Meshes, true)                                    \
      ->Unit(benchmark::kMillisecond)                                               \
      ->Iterations(3)

QUALITY_CASES(bunny);
QUALITY_CASES(horse);
QUALITY_CASES(dragon);
GALERKIN_CASES(bunny);
GALERKIN_CASES(horse);
GALERKIN_CASES(dragon);
BENCHMARK(BM_StreamTriad)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace corofem::bench
