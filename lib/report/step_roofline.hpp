#pragma once
// The roofline of a time step: per phase of the paper's step (linearly implicit
// Euler, energy-newton rotations, MG-PCG with the gather update, the default) the bytes it must
// move and the flops it must do, counted from the sizes of the data structures it touches, and the
// floor that the machine's measured roofs put under its time: max(bytes / STREAM bandwidth, flops /
// dense-product rate).
//
// Bytes are compulsory traffic: every array a phase reads or writes counted once per pass over
// it (vertex arrays gathered through the tets once, not per element), a member read out of a
// larger per-element struct as the cache lines it spans. It is a floor: a kernel that moves more
// (re-reads a block that fell out of cache, write-allocates) is above it by that much. Where
// the data fit in the caches a phase can run below it; `working_set_bytes` says when.
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "fem/fe_problem.hpp"
#include "sparse/matrix_traffic.hpp"

namespace corofem {

class MultigridSolver;

/// The update phase's parts (multigrid/multigrid_parts.hpp): galerkin, smoothers, coarsest.
/// `refactor_share`: the share of the updates that factorized the coarsest level (the others kept
/// its factor: MultigridSummary::refactor_share).
std::map<std::string, Traffic> update_traffic(const MultigridSolver& solver,
                                              double refactor_share = 1);

/// Per step, the phases checks, rotate, assemble, forces, system, update and solve.
/// `newton_iterations`: mean energy-newton iterations per element; `solve_iterations`: MG-PCG
/// iterations of the step. The coarsest level's factorization and substitutions are counted
/// from CHOLMOD's own analysis (entries of L, flops); `refactor_share` as for update_traffic.
std::map<std::string, Traffic> step_traffic(const FeProblem& problem, const MultigridSolver& solver,
                                            double newton_iterations, double solve_iterations,
                                            double refactor_share = 1);

/// The machine's measured roofs (core/machine_roofs.hpp).
struct MachineRoofs {
  double stream_gbps = 0;   ///< STREAM triad, GB/s
  double dense_gflops = 0;  ///< dense matrix product, Gflop/s
};

/// {"stream_triad_GBps", "dense_gflops", "working_set_bytes", "floor_ms", "step_ms",
///  "over_floor", "phases": {phase: {"bytes", "flops", "flops_per_byte",
///  "floor_ms", "bound" (memory or compute), "measured_ms", "over_floor"}}}; `measured_ms` per
/// phase and "step". TimedRun::roofline adds "update_parts" in the same form and "untimed_ms".
nlohmann::json roofline_record(const std::map<std::string, Traffic>& traffic,
                               const std::map<std::string, double>& measured_ms,
                               const MachineRoofs& roofs, double working_set_bytes);

}  // namespace corofem
