#include "scene/load_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "fem/loads.hpp"

namespace corofem {

namespace {

/// How many of `vertices` (a selection in this rank's part) the whole body has: each rank counts
/// its owned ones.
int whole_body_count(const std::vector<int>& vertices, const RankView& ranks) {
  if (!ranks.distributed()) return static_cast<int>(vertices.size());
  const auto owned = std::count_if(vertices.begin(), vertices.end(),
                                   [&](int v) { return v < ranks.owned_vertices; });
  return static_cast<int>(std::lround(ranks.sum(static_cast<double>(owned))));
}

}  // namespace

LoadSchedule::LoadSchedule(const Scene& scene, const FeProblem& problem, const RankView& ranks)
    : gravity_(Eigen::VectorXd::Zero(problem.num_dofs())), supports_(problem.dirichlet) {
  if (scene.gravity.norm() > 0)
    gravity_ = gravity_load(problem.mesh, problem.materials, scene.gravity);
  for (const ForceSpec& force : scene.forces) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(problem.num_dofs());
    const std::vector<int> vertices = vertices_in_box(problem.mesh.rest, force.box);
    add_spread_force(f, vertices, force.total, whole_body_count(vertices, ranks));
    forces_.push_back(std::move(f));
    force_timing_.push_back(force.timing);
  }
  for (std::size_t i = 0; i < scene.moves.size(); ++i) {
    auto vertices = vertices_in_box(problem.mesh.rest, scene.moves[i].box);
    if (whole_body_count(vertices, ranks) == 0)
      throw InputError("scene '" + scene.name + "': moves[" + std::to_string(i) +
                       "].box selects no vertex of the mesh");
    moves_.push_back(scene.moves[i]);
    move_vertices_.push_back(std::move(vertices));
  }
}

void LoadSchedule::apply(int step, FeProblem& problem) const {
  problem.external_force = gravity_;
  for (std::size_t i = 0; i < forces_.size(); ++i)
    if (const double s = force_timing_[i].factor(step); s != 0)
      problem.external_force += s * forces_[i];
  problem.dirichlet = supports_;
  for (std::size_t i = 0; i < moves_.size(); ++i) {
    const MoveSpec& move = moves_[i];
    const LoadTiming& t = move.timing;
    if (t.release_step > 0 && step >= t.release_step) continue;  // released: free vertices
    const double s = t.factor(step);
    const Mat3 rotation =
        Eigen::AngleAxisd(s * move.degrees * std::numbers::pi / 180, move.axis).toRotationMatrix();
    for (int v : move_vertices_[i]) {
      const Vec3& x = problem.mesh.rest[v];
      problem.dirichlet.fix_vertex(
          v, s * move.translate + (rotation - Mat3::Identity()) * (x - move.center));
    }
  }
}

int projected_start_history(const AnalysisSpec& a, bool distributed_mesh) {
  const bool applies = a.type == AnalysisType::Dynamic &&
                       a.integrator == Integrator::LinearImplicit &&
                       a.formulation == Formulation::Corotational &&
                       a.solver != SolverKind::Cholmod && !distributed_mesh;
  return applies && a.start == SolveStart::Projection ? a.start_history : 0;
}

DynamicOptions dynamic_options(const Scene& scene, FeProblem& problem, RankView ranks) {
  const AnalysisSpec& a = scene.analysis;
  DynamicOptions options{a.formulation == Formulation::Corotational,
                         a.dt,
                         a.steps,
                         a.rayleigh_alpha,
                         a.rayleigh_beta,
                         {}};
  options.newton = a.integrator == Integrator::Newton;
  options.newton_settings.tolerance = a.tolerance;
  options.newton_settings.max_iterations = a.max_iterations;
  options.max_step_cuts = a.max_step_cuts;
  options.factorization = a.factorization;
  options.start_history = projected_start_history(a, ranks.distributed());
  auto schedule = std::make_shared<const LoadSchedule>(scene, problem, ranks);
  options.ranks = std::move(ranks);
  schedule->apply(1, problem);
  options.before_step = [schedule](int step, FeProblem& p) { schedule->apply(step, p); };
  return options;
}

}  // namespace corofem
