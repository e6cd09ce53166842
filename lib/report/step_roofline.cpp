#include "report/step_roofline.hpp"

#include <algorithm>
#include <cmath>

#include "multigrid/multigrid_solver.hpp"
#include "rotation/element_quadrature.hpp"

namespace corofem {
namespace {

constexpr double kVec3 = 24;

/// One V-cycle from level h (multigrid_solver.cpp vcycle), x = 0 on entry on every level.
Traffic vcycle(const MultigridSolver& solver, int h) {
  const MultigridHierarchy& hierarchy = solver.hierarchy();
  if (h == hierarchy.num_levels() - 1) {
    // CHOLMOD's forward and backward substitution: L read twice, 2 flops per entry each way.
    const double lnz = solver.coarsest_factor_nonzeros(), n = 3.0 * hierarchy.matrix(h).block_rows;
    return {16 * lnz + 32 * n, 4 * lnz};
  }
  const BrcMatrix& a = hierarchy.matrix(h);
  const Transfer& t = hierarchy.transfer(h);
  const double n = 3.0 * a.block_rows, coarse = 3.0 * t.coarse;
  const int pre = solver.params().pre_smoothing, post = solver.params().post_smoothing;
  const Smoother& smoother = solver.smoother(h);
  Traffic out = smoother.pre_traffic(a, pre);
  out += smoother.post_traffic(a, post);
  if (!smoother.forms_residual(pre)) {
    out += matvec_traffic(a);
    out += {24 * n, n};  // r = b - A x
  }
  const double r_entries = static_cast<double>(t.r_weight.size());
  const double p_entries = static_cast<double>(t.p_weight.size());
  out += {12 * r_entries + 8 * n + 8 * coarse, 6 * r_entries};  // restrict
  out += vcycle(solver, h + 1);
  out += {12 * p_entries + 8 * coarse + 16 * n, 6 * p_entries};  // prolongate and add
  return out;
}

/// One factorization of the coarsest level: its values converted to CHOLMOD's lower-triangular
/// CSC (about half the blocks, 12 B an entry) and factorized: L written, and the flops CHOLMOD's
/// analysis counted.
Traffic coarsest_factorization(const MultigridSolver& solver) {
  const BrcMatrix& coarsest = solver.hierarchy().matrix(solver.hierarchy().num_levels() - 1);
  return {kBlockBytes * static_cast<double>(coarsest.col_index.size()) * (1 + 12.0 / 8 / 2) +
              8 * solver.coarsest_factor_nonzeros(),
          solver.coarsest_factorization_flops()};
}

/// Every update's check of how far the coarsest values moved: them and the factored copy read.
Traffic coarsest_check(const MultigridSolver& solver) {
  const BrcMatrix& coarsest = solver.hierarchy().matrix(solver.hierarchy().num_levels() - 1);
  return {2 * kBlockBytes * static_cast<double>(coarsest.col_index.size()),
          3.0 * static_cast<double>(coarsest.values.size())};
}

}  // namespace

std::map<std::string, Traffic> update_traffic(const MultigridSolver& solver,
                                              double refactor_share) {
  // Galerkin: per coarse level the stream (control and data, or the gather's pairs and block
  // lists) and A_{h-1} read once, E_h written (18 flops per pair: a 3x3 block scaled and added),
  // its mirror pairs. The step hands the fine values over (take_matrix): no copy.
  const MultigridHierarchy& h = solver.hierarchy();
  // The stream of the method in use (the symmetric one stands in for the methods without one).
  const GalerkinMethod method = solver.params().galerkin;
  const auto stream = [&](int level) -> std::pair<std::size_t, std::size_t> {  // {bytes, pairs}
    if (method == GalerkinMethod::Gather)
      return {h.gather(level).bytes(), h.gather(level).num_pairs()};
    const GalerkinStream& s =
        method == GalerkinMethod::StreamFull ? h.full_stream(level) : h.stream(level);
    return {s.bytes(), s.num_pairs()};
  };
  std::map<std::string, Traffic> parts;
  Traffic galerkin;
  for (int level = 1; level < h.num_levels(); ++level) {
    const BrcMatrix& coarse = h.matrix(level);
    const double coarse_blocks = static_cast<double>(coarse.col_index.size());
    const auto [bytes, pairs] = stream(level - 1);
    galerkin += {static_cast<double>(bytes) +
                     kBlockBytes * static_cast<double>(h.matrix(level - 1).col_index.size()) +
                     kBlockBytes * coarse_blocks + 8 * (coarse_blocks - coarse.block_rows) / 2,
                 18.0 * static_cast<double>(pairs)};
  }
  parts["galerkin"] = galerkin;
  // The smoothers' set-up, as each counts its own.
  Traffic smoothers;
  for (int level = 0; level + 1 < h.num_levels(); ++level)
    smoothers += solver.smoother(level).setup_traffic(h.matrix(level));
  parts["smoothers"] = smoothers;
  // The coarsest level: its factorization in the updates that refactor it, in every update the
  // check of how far its values moved.
  parts["coarsest"] = refactor_share * coarsest_factorization(solver);
  parts["coarsest"] += coarsest_check(solver);
  return parts;
}

std::map<std::string, Traffic> step_traffic(const FeProblem& problem, const MultigridSolver& solver,
                                            double newton_iterations, double solve_iterations,
                                            double refactor_share) {
  const double e = problem.mesh.num_tets(), v = problem.mesh.num_vertices(), n = 3 * v;
  const BrcMatrix& k = problem.stiffness;
  const double blocks = static_cast<double>(k.col_index.size());
  const double tets = sizeof(Tet) * e, rotations = kBlockBytes * e;
  std::map<std::string, Traffic> t;
  // The finiteness checks of b and u (entries and squared norm); energy-newton counts the
  // inverted elements on its way (the sign of det S, 14 flops a tet, below).
  t["checks"] = {16 * n, 4 * n};
  // positions p = x + u; energy-newton per tet: its moment arms, the deformed moment (S and a:
  // 120 flops), Horn's matrix and the warm start (about 80), 250 per Newton iteration (eqs. 5-8:
  // N q, gradient, Hessian, a 4x4 Cholesky and two solves) and 60 for the final gradient check,
  // the rotation matrix (35), det S (14); the previous rotation read, the new one written.
  t["rotate"] = {3 * kVec3 * v + tets + kVec3 * v + sizeof(MomentArms) * e + 2 * rotations,
                 3 * v + (311 + 250 * newton_iterations) * e};
  // Ktilde_e from the rotated gradients h_a = Q g_a (4 x 15 flops; per block b >= a,
  // V lambda h_a h_b^T + V mu h_b h_a^T + V mu (g_a . g_b) I: 35), 16 block += (9), and the
  // elastic force Q K_e s_e (strain 117, K_e s from the gradients 138, rotate back 4 x 18);
  // the gradients and V lambda, V mu read out of ElementRest, the 16 target blocks of the
  // assembly map, rest positions and displacements, the step's matrix written once (zeroing
  // fused; the mass read and added into its diagonal), the force written.
  t["assemble"] = {rotations + cache_lines(4 * kVec3 + 16) * e + sizeof(std::array<int, 16>) * e +
                       tets + kVec3 * v + 8 * n + kBlockBytes * blocks + 8 * n + 8 * n,
                   (60 + 10 * 35 + 16 * 9 + 117 + 138 + 72) * e};
  // b = M v + dt (f_ext - f_int), f_int from the assembly: mass, velocity, external force and
  // f_int read, b written.
  t["forces"] = {4 * 8 * n + 8 * n, 5 * n};
  // A = (1 + dt alpha) M + (dt beta + dt^2) Ktilde: the assembly wrote it (above). Its supports:
  // the velocity's prescribed values (fixed flags, prescribed displacements and u read, values
  // written), the supported vertices' rows and columns (their blocks read and written, with
  // their column indices), b's entries.
  double supported_blocks = 0;
  const std::vector<char> supported = problem.dirichlet.supported_vertices();
  for (int i = 0; i < k.block_rows; ++i)
    if (supported[i]) supported_blocks += 2 * (k.row_start[i + 1] - k.row_start[i]);
  t["system"] = {n + 3 * 8 * n + n + supported_blocks * (2 * kBlockBytes + kIndexBytes) + 16 * n,
                 2 * n + 18 * supported_blocks};
  // The coarsest factorization and the smoothers' set-up count where they run: in the solve
  // when the solver defers them to it (MultigridSolver::defers_update), which it does in the
  // updates that refactor; the check that decides it runs in every update.
  Traffic update, deferred;
  const double share = solver.defers_update() ? refactor_share : 0;
  for (const auto& [part, traffic] : update_traffic(solver, refactor_share)) {
    if (part == "smoothers") {
      deferred += share * traffic;
      update += (1 - share) * traffic;
    } else if (part == "coarsest" && share > 0) {
      deferred += share * coarsest_factorization(solver);
      update += coarsest_check(solver);
    } else {
      update += traffic;
    }
  }
  t["update"] = update;
  // MG-PCG (linalg/preconditioned_cg.cpp): per iteration A p, one V-cycle and 14 vector passes
  // (two dots, two axpys, a norm, p = z + beta p); the start: r = b - A x, norms, r.z.
  const Traffic cycle = vcycle(solver, 0);
  Traffic solve = (solve_iterations + 1) * matvec_traffic(solver.hierarchy().matrix(0));
  solve += solve_iterations * cycle;
  solve += {(14 * solve_iterations + 9) * 8 * n, (12 * solve_iterations + 6) * n};
  solve += deferred;
  t["solve"] = solve;
  return t;
}

nlohmann::json roofline_record(const std::map<std::string, Traffic>& traffic,
                               const std::map<std::string, double>& measured_ms,
                               const MachineRoofs& roofs, double working_set_bytes) {
  nlohmann::json phases = nlohmann::json::object();
  double floor_total = 0;
  for (const auto& [phase, t] : traffic) {
    const auto it = measured_ms.find(phase);
    const double memory_ms = t.bytes / (roofs.stream_gbps * 1e9) * 1e3;
    const double compute_ms = t.flops / (roofs.dense_gflops * 1e9) * 1e3;
    const double floor_ms = std::max(memory_ms, compute_ms);
    floor_total += floor_ms;
    nlohmann::json record = {{"bytes", t.bytes},
                             {"flops", t.flops},
                             {"flops_per_byte", t.bytes > 0 ? t.flops / t.bytes : 0.0},
                             {"floor_ms", floor_ms},
                             {"bound", memory_ms >= compute_ms ? "memory" : "compute"}};
    if (it != measured_ms.end()) {
      record["measured_ms"] = it->second;
      record["over_floor"] = floor_ms > 0 ? it->second / floor_ms : 0.0;
    }
    phases[phase] = record;
  }
  nlohmann::json out = {{"stream_triad_GBps", roofs.stream_gbps},
                        {"dense_gflops", roofs.dense_gflops},
                        {"working_set_bytes", working_set_bytes},
                        {"phases", phases},
                        {"floor_ms", floor_total}};
  if (const auto step = measured_ms.find("step"); step != measured_ms.end()) {
    out["step_ms"] = step->second;
    out["over_floor"] = step->second / floor_total;
  }
  return out;
}

}  // namespace corofem
