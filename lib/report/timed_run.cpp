#include "report/timed_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "io/solver_record.hpp"
#include "mesh/vertex_selection.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "multigrid/transfer.hpp"
#include "report/report_oracles.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene_simulation.hpp"
#include "solver/petsc_galerkin.hpp"
#include "solver/petsc_solver.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {
namespace {

/// Passes everything to the solver under test; on the checked steps also solves the same system
/// with CHOLMOD. The oracle's time lands in those steps' solve phase, so they are left out of the
/// medians.
class OracleCheckedSolver : public LinearSolver {
 public:
  OracleCheckedSolver(std::unique_ptr<LinearSolver> inner, std::vector<int> check_steps,
                      TimedRun& out)
      : inner_(std::move(inner)), check_steps_(std::move(check_steps)), out_(out) {}
  std::string name() const override { return inner_->name(); }
  const MultigridSolver* multigrid() const override { return inner_->multigrid(); }
  const SolverChoice* choice() const override { return inner_->choice(); }
  void set_matrix(const BrcMatrix& a) override {
    if (next_is_checked()) matrix_ = to_eigen(a);
    inner_->set_matrix(a);
  }
  void take_matrix(BrcMatrix& a) override {
    if (next_is_checked()) matrix_ = to_eigen(a);  // before the solver takes the values
    inner_->take_matrix(a);
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    const SolveStats stats = inner_->solve(b, x);
    if (checking_) {
      const Eigen::VectorXd exact = report_oracles("direct_solve").direct_solve(matrix_, b);
      const double norm = exact.norm();
      const double error = norm > 0 ? (x - exact).norm() / norm : (x - exact).norm();
      out_.solve_error_max = std::max(out_.solve_error_max, error);
      out_.solve_residual_max = std::max(out_.solve_residual_max, stats.residual);
    }
    return stats;
  }

 private:
  bool next_is_checked() {
    ++call_;
    checking_ = std::find(check_steps_.begin(), check_steps_.end(), call_) != check_steps_.end();
    return checking_;
  }

  std::unique_ptr<LinearSolver> inner_;
  std::vector<int> check_steps_;
  TimedRun& out_;
  int call_ = 0;
  bool checking_ = false;
  Eigen::SparseMatrix<double> matrix_;
};

double total_volume(const TetMesh& mesh, const std::vector<Vec3>& x) {
  double v = 0;
  for (const Tet& t : mesh.tets) v += signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  return v;
}

}  // namespace

std::vector<double> TimedRun::phase_ms(const std::string& phase, int warmup) const {
  std::vector<double> values;
  for (std::size_t s = warmup; s < step_ms.size(); ++s) {
    auto it = step_ms[s].find(phase);
    if (it != step_ms[s].end() && !step_ms[s].count("checked")) values.push_back(it->second);
  }
  return values;
}

double TimedRun::median_ms(const std::string& phase, int warmup) const {
  return median(phase_ms(phase, warmup));
}

nlohmann::json TimedRun::samples_ms(int warmup) const {
  nlohmann::json out = nlohmann::json::object();
  for (const char* phase : {"rotate", "assemble", "update", "solve", "step"}) {
    nlohmann::json values = nlohmann::json::array();
    for (double ms : phase_ms(phase, warmup)) values.push_back(rounded_sample_ms(ms));
    if (!values.empty()) out[phase] = std::move(values);
  }
  return out;
}

double TimedRun::median_iterations(int warmup) const {
  std::vector<double> values;
  for (std::size_t s = warmup; s < solves.size(); ++s) values.push_back(solves[s].iterations);
  return median(values);
}

nlohmann::json TimedRun::roofline(int warmup, const MachineRoofs& roofs) const {
  if (traffic.empty()) return nullptr;
  std::map<std::string, double> measured;
  for (const auto& [phase, t] : traffic) measured[phase] = median_ms(phase, warmup);
  measured["step"] = median_ms("step", warmup);
  nlohmann::json record = roofline_record(traffic, measured, roofs, working_set_bytes);
  // The update's parts, timed by the multigrid solver (means over every update of the run).
  std::map<std::string, double> parts;
  if (multigrid)
    for (const auto& [part, ms] : named_parts(multigrid->update))
      if (ms != 0) parts[part] = ms;  // as the record: a part that did not run is absent
  record["update_parts"] =
      roofline_record(update_traffic, parts, roofs, working_set_bytes)["phases"];
  // Work of a step outside every named phase: each step's own remainder, then the median (a
  // difference of medians is not a median of differences, and can be negative).
  std::vector<double> untimed;
  for (std::size_t s = warmup; s < step_ms.size(); ++s) {
    if (step_ms[s].count("checked")) continue;
    double rest = step_ms[s].at("step");
    for (const auto& [phase, ms] : step_ms[s])
      if (traffic.count(phase)) rest -= ms;
    untimed.push_back(rest);
  }
  record["untimed_ms"] = median(untimed);
  return record;
}

Vec3 TimedRun::probe(const nlohmann::json& box) const {
  const Vec3 lo(box[0][0].get<double>(), box[0][1].get<double>(), box[0][2].get<double>());
  const Vec3 hi(box[1][0].get<double>(), box[1][1].get<double>(), box[1][2].get<double>());
  const std::vector<int> vertices = vertices_in_box(mesh.rest, {lo, hi});
  Vec3 sum = Vec3::Zero();
  for (int v : vertices) sum += result.displacement.segment<3>(3 * v);
  return vertices.empty() ? Vec3::Zero() : Vec3(sum / static_cast<double>(vertices.size()));
}

namespace {

/// PETSc's MatPtAP in numeric-reuse mode, the Galerkin product a PETSc user would call, on the
/// same matrices as the hierarchy's last update: median ms of 5 after the symbolic one.
double matptap_ms(const MultigridHierarchy& h) {
  std::vector<Transfer> transfers;
  for (int level = 0; level + 1 < h.num_levels(); ++level) transfers.push_back(h.transfer(level));
  PetscPtapHierarchy ptap(h.matrix(0), transfers);
  ptap.update(h.matrix(0));  // the symbolic phase, untimed
  std::vector<double> ms;
  for (int k = 0; k < 5; ++k) {
    const auto start = std::chrono::steady_clock::now();
    ptap.update(h.matrix(0));
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  return median(ms);
}

/// The operators of the run's final state against the oracles: every coarse level against Eigen's
/// R A R^T, and energy-newton's rotations against the exact minimizer.
void check_operators(SceneSimulation& simulation, const LinearSolver& solver,
                     const std::vector<Vec3>& final_positions, TimedRun& out) {
  const FeProblem& problem = simulation.problem();
  if (const MultigridSolver* mg = solver.multigrid()) {
    const MultigridHierarchy& h = mg->hierarchy();
    out.galerkin_error_max = 0;
    for (int level = 0; level + 1 < h.num_levels(); ++level) {
      const Eigen::SparseMatrix<double> expected =
          report_oracles("galerkin")
              .galerkin(restriction_matrix(h.transfer(level)), to_eigen(h.matrix(level)));
      const double error = (to_eigen(h.matrix(level + 1)) - expected).norm() / expected.norm();
      out.galerkin_error_max = std::max(out.galerkin_error_max, error);
    }
  }
  if (simulation.scene().analysis.rotation == RotationMethod::EnergyNewton &&
      simulation.corotational()) {
    auto exact = make_rotation_extractor(RotationMethod::EnergyExact, problem.mesh);
    std::vector<Mat3> newton = out.result.rotations, oracle = out.result.rotations;
    simulation.extractor().extract(final_positions, newton);
    exact->extract(final_positions, oracle);
    out.rotation_error_max_rad = 0;
    for (std::size_t e = 0; e < newton.size(); ++e)
      out.rotation_error_max_rad =
          std::max(out.rotation_error_max_rad, angle_between(newton[e], oracle[e]));
    out.rotation_elements_compared = static_cast<int>(newton.size());
  }
}

}  // namespace

TimedRun timed_run(const nlohmann::json& scene_json, const std::string& name,
                   const TimedRunOptions& options) {
  TimedRun out;
  SceneSimulation simulation(parse_scene(scene_json, ".", name));
  FeProblem& problem = simulation.problem();
  out.tets = problem.mesh.num_tets();
  out.vertices = problem.mesh.num_vertices();
  out.mesh = problem.mesh;
  if (!options.check_steps.empty())
    simulation.set_solver(std::make_unique<OracleCheckedSolver>(simulation.release_solver(),
                                                                options.check_steps, out));
  if (options.on_step) simulation.keep_stiffness();  // it gets the problem, Ktilde included
  const MultigridSolver* mg = simulation.solver().multigrid();
  if (mg) out.levels = mg->hierarchy().num_levels();
  out.result = simulation.run([&](const StepState& s) {
    auto phases = s.phase_ms;
    if (std::find(options.check_steps.begin(), options.check_steps.end(), s.step) !=
        options.check_steps.end())
      phases["checked"] = 1;  // the oracle solve ran inside this step's solve phase
    out.step_ms.push_back(std::move(phases));
    out.solves.push_back(s.solve);
    const auto& iterations = simulation.extractor().stats().iterations;
    double sum = 0;
    for (std::uint8_t i : iterations) sum += i;
    out.rotation_iterations.push_back(
        iterations.empty() ? 0.0 : sum / static_cast<double>(iterations.size()));
    if (options.on_step) options.on_step(s, problem);
  });
  out.multigrid = simulation.multigrid_summary(simulation.solver());
  if (mg) {
    const int warmup = std::min<int>(options.warmup_steps, static_cast<int>(out.solves.size()) - 1);
    const std::vector<double> after(out.rotation_iterations.begin() + std::max(warmup, 0),
                                    out.rotation_iterations.end());
    const double refactor_share = out.multigrid ? out.multigrid->refactor_share() : 1.0;
    out.traffic = step_traffic(problem, *mg, median(after),
                               out.median_iterations(std::max(warmup, 0)), refactor_share);
    out.update_traffic = update_traffic(*mg, refactor_share);
    const MultigridHierarchy& h = mg->hierarchy();
    out.working_set_bytes = static_cast<double>(sizeof(ElementRest) * problem.elements.size()) +
                            static_cast<double>(h.stream_bytes(mg->params().galerkin));
    for (int level = 0; level < h.num_levels(); ++level)
      out.working_set_bytes += 76.0 * static_cast<double>(h.matrix(level).col_index.size());
  }
  if (mg && options.time_matptap && have_petsc()) out.matptap_ms = matptap_ms(mg->hierarchy());
  out.rest_volume = total_volume(problem.mesh, problem.mesh.rest);
  const auto final_positions = problem.positions(out.result.displacement);
  out.final_volume = total_volume(problem.mesh, final_positions);
  if (options.check_operators)
    check_operators(simulation, simulation.solver(), final_positions, out);
  return out;
}

}  // namespace corofem
