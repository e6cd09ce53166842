#include "cli/run_scene.hpp"

#include <unistd.h>

#include <Eigen/LU>
#include <algorithm>
#include <iostream>
#include <ostream>
#include <string>

#include "cli/rank_records.hpp"
#include "cli/static_progress.hpp"
#include "cli/step_progress.hpp"
#include "core/memory_usage.hpp"
#include "core/number_text.hpp"
#include "core/statistics.hpp"
#include "core/threads.hpp"
#include "io/phase_counts_record.hpp"
#include "io/run_context.hpp"
#include "io/solver_record.hpp"
#include "io/vtu_writer.hpp"
#include "rotation/quaternion.hpp"
#include "scene/load_schedule.hpp"
#include "scene/scene_simulation.hpp"
#include "scene/solver_factory.hpp"
#include "solver/mpi_launch.hpp"

namespace corofem {

namespace {

/// What the run did: a dynamic run's steps and solves (its equilibrium residual says only how far
/// from rest it ended), a static run's convergence to equilibrium.
std::string closing_line(const Scene& scene, SimulationResult& result) {
  std::string line = "corofem: ";
  if (scene.analysis.type == AnalysisType::Dynamic) {
    line +=
        std::to_string(result.steps) + " steps, " +
        general_number(static_cast<double>(result.linear_iterations) / std::max(result.steps, 1)) +
        " solver iterations per step, last solve's relative residual " +
        general_number(result.last_solve_residual);
  } else {
    line += std::string(result.converged ? "converged" : "did not converge") + ", " +
            std::to_string(result.iterations) + " iterations, residual " +
            general_number(result.residual);
    if (result.increment_cuts > 0)
      line += " (load increments halved " + std::to_string(result.increment_cuts) + "x)";
  }
  return line + ", " + general_number(result.timings_ms["total"]) + " ms\n";
}

/// The record's solver: a corotated Newton run names how its tangent is solved.
std::string newton_solver_name(NewtonTangent tangent, SolverKind kind, const std::string& solver) {
  switch (tangent) {
    case NewtonTangent::ByGmres:
      return is_petsc_solver(kind)
                 ? solver + " (GMRES), Newton"
                 : "GMRES preconditioned by " + solver +
                       " on the symmetric part (where that is indefinite, on the corotated "
                       "stiffness; the sparse factorizations where both fail), Newton";
    case NewtonTangent::Factored:
      return "sparse LU (UMFPACK), Newton";
    case NewtonTangent::None:
      break;
  }
  return solver;
}

/// The record's summary: provenance, the mesh, the analysis as run, convergence and timings.
nlohmann::json run_summary(SceneSimulation& simulation, const SimulationResult& result) {
  const Scene& scene = simulation.scene();
  const FeProblem& problem = simulation.problem();
  const MeshValidation& validation = simulation.validation();
  const AnalysisSpec& a = scene.analysis;
  const bool corotational = simulation.corotational();
  const RotationExtractor* extractor = &simulation.extractor();
  const LinearSolver* solver = &simulation.solver();
  nlohmann::json r;
  r["producer"] = "corofem run";
  r["context"] = run_context();
  r["scene"] = scene.raw;
  r["scene_file"] = scene.name;
  r["mesh"] = {{"vertices", problem.mesh.num_vertices()},
               {"tets", problem.mesh.num_tets()},
               {"reoriented_tets", validation.reoriented},
               {"unused_vertices_removed", validation.unused_removed}};
  r["analysis"] = {
      {"type", kAnalysisTypes.name(a.type)},
      {"formulation", kFormulations.name(a.formulation)},
      {"integrator", kIntegrators.name(a.integrator)},
      {"rotation", (corotational ? a.rotation : RotationMethod::None).name()},
      {"rotation_params", to_json(a.rotation_params)},
      {"solver", newton_solver_name(newton_tangent(a.type, a.integrator, a.formulation, a.solver),
                                    a.solver, solver->name())}};
  if (a.type == AnalysisType::Dynamic && a.integrator == Integrator::LinearImplicit) {
    // What the solves started from: a projection only where it applies (load_schedule.hpp).
    const int history = projected_start_history(a, simulation.part().has_value());
    r["analysis"]["start"] = history > 0
                                 ? nlohmann::json{{"kind", "projection"}, {"history", history}}
                                 : nlohmann::json{{"kind", "extrapolation"}};
  }
  if (const MultigridSolver* mg = solver->multigrid()) {
    r["analysis"]["multigrid"] = to_json(mg->params());
    r["multigrid"] = simulation.describe_multigrid(*mg);
  }
  if (const SolverChoice* choice = solver->choice()) r["solver_choice"] = to_json(*choice);
  r["converged"] = result.converged;
  if (!result.converged) r["message"] = result.message;
  r["iterations"] = result.iterations;
  r["steps"] = result.steps;
  r["linear_iterations"] = result.linear_iterations;
  if (scene.analysis.type == AnalysisType::Dynamic)
    r["last_solve_residual"] = result.last_solve_residual;
  else
    r["load_increment_cuts"] = result.increment_cuts;
  if (simulation.tangent_solve() == TangentSolve::PreconditionedBySolver) {
    r["tangent_standin_solves"] = result.tangent_fallbacks.standin;
    r["tangent_factored_solves"] = result.tangent_fallbacks.factored;
  }
  r["residual"] = result.residual;
  r["inverted_max"] = result.inverted_max;
  r["timings_ms"] = result.timings_ms;
  r["peak_rss_kb"] = peak_rss_kb();
  r["rotation_stats"] = {
      {"last_fallbacks", extractor->stats().fallbacks},
      {"last_iterations_max", extractor->stats().iterations.empty()
                                  ? 0
                                  : *std::max_element(extractor->stats().iterations.begin(),
                                                      extractor->stats().iterations.end())}};
  return r;
}

/// The fields of the final state: rest positions and displacements per vertex, and with
/// output.rotations each element's rotation of the final displacement.
void add_fields(SceneSimulation& simulation, const SimulationResult& result, nlohmann::json& r) {
  const Scene& scene = simulation.scene();
  const FeProblem& problem = simulation.problem();
  RotationExtractor* extractor = &simulation.extractor();
  r["node_tags"] = problem.mesh.node_tags;
  nlohmann::json rest = nlohmann::json::array(), disp = nlohmann::json::array();
  for (int v = 0; v < problem.mesh.num_vertices(); ++v) {
    const Vec3& x = problem.mesh.rest[v];
    rest.push_back({x.x(), x.y(), x.z()});
    disp.push_back({result.displacement[3 * v], result.displacement[3 * v + 1],
                    result.displacement[3 * v + 2]});
  }
  r["rest"] = std::move(rest);
  r["displacement"] = std::move(disp);
  if (scene.output.rotations) {
    // Rotations of the final displacement (not the lagged ones of the last solve).
    std::vector<Mat3> final_rotations = result.rotations;
    extractor->extract(problem.positions(result.displacement), final_rotations);
    nlohmann::json quats = nlohmann::json::array(), reflected = nlohmann::json::array();
    for (int e = 0; e < problem.mesh.num_tets(); ++e) {
      const auto q = to_quaternion(final_rotations[e]);
      quats.push_back({q.w(), q.x(), q.y(), q.z()});
      if (final_rotations[e].determinant() < 0) reflected.push_back(problem.mesh.element_tags[e]);
    }
    r["element_tags"] = problem.mesh.element_tags;
    r["rotations"] = std::move(quats);
    r["reflected_elements"] = std::move(reflected);
  }
}

}  // namespace

SceneRun run_scene(const Scene& scene, std::ostream* progress,
                   const std::optional<PhaseCounting>& counting) {
  if (progress) *progress << "corofem: building '" << scene.name << "'\n";
  const MpiLaunch mpi = mpi_launch();
  SceneSimulation simulation = SceneSimulation::distributes_mesh(scene, mpi.size)
                                   ? SceneSimulation(scene, mpi.rank, mpi.size)
                                   : SceneSimulation(scene);
  const std::optional<RankPart>& part = simulation.part();
  FeProblem& problem = simulation.problem();
  const int tets = part ? part->global_tets : problem.mesh.num_tets();
  const int vertices = part ? part->global_vertices : problem.mesh.num_vertices();
  if (progress) {
    *progress << "corofem: " << tets << " tets, " << vertices << " vertices; "
              << kAnalysisTypes.name(scene.analysis.type) << " "
              << kFormulations.name(scene.analysis.formulation) << " analysis\n";
    if (part)
      *progress << "corofem: distributed over " << mpi.size << " ranks; rank 0 holds "
                << problem.mesh.num_tets() << " tets (" << part->owned_tets() << " its own), "
                << part->owned_vertices << " vertices and " << part->halo_vertices
                << " of the halo\n";
  }
  StepProgress steps(progress, progress == &std::cerr && isatty(STDERR_FILENO),
                     scene.analysis.steps, !counting);
  // A counted static run reports no iterations: their lines follow the clock (see StepProgress).
  StaticProgress iterations(counting ? nullptr : progress,
                            progress == &std::cerr && isatty(STDERR_FILENO),
                            scene.analysis.tolerance);
  // Counted from here: the steps, not the set-up.
  std::unique_ptr<SectionCounter> counter;
  std::string not_counted;
  if (counting) {
    counter = SectionCounter::start(counting->source, not_counted, counting->callgrind_file);
    if (!counter && progress) *progress << "corofem: phases not counted: " << not_counted << "\n";
    simulation.mark_sections(counter.get());
  }
  // Every step's phase times, the evidence behind timings_ms for `corofem compare`.
  nlohmann::json step_samples = nlohmann::json::object();
  SimulationResult result = simulation.run(
      [&](const StepState& s) {
        for (const auto& [phase, ms] : s.phase_ms)
          step_samples[phase].push_back(rounded_sample_ms(ms));
        steps.step_done(s.step);
      },
      [&](const StaticIteration& at) { iterations.iteration_done(at); });

  if (counter) {
    simulation.mark_sections(nullptr);
    counter->finish();
  }

  nlohmann::json r = run_summary(simulation, result);
  if (!step_samples.empty()) r["step_samples_ms"] = std::move(step_samples);
  if (counting)
    r["phase_counts"] = counter ? to_json(*counter, thread_count())
                                : unavailable_counts(counting->source, not_counted);
  if (part) {
    r["mesh"]["vertices"] = vertices;
    r["mesh"]["tets"] = tets;
    r["ranks"] = rank_table(simulation, result);
    r["ranks"]["partitioner"] = simulation.partitioner();
    add_gathered_fields(simulation, result, r);
    if (scene.output.vtu) r["vtu"] = write_rank_pieces(simulation, result, *scene.output.vtu);
  } else {
    add_fields(simulation, result, r);
    if (scene.output.vtu) {
      write_vtu(*scene.output.vtu, problem.mesh, result.displacement, result.rotations);
      r["vtu"] = scene.output.vtu->string();
    }
  }
  steps.end_line();
  iterations.end_line();
  if (progress) *progress << closing_line(scene, result);
  return {std::move(r), result.converged};
}

}  // namespace corofem
