#include "tune/candidate_run.hpp"

#include <algorithm>
#include <vector>

#include "core/errors.hpp"
#include "core/statistics.hpp"
#include "report/stability_study.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {

CandidateRun run_candidate(const nlohmann::json& scene_json, const std::filesystem::path& base_dir,
                           const std::string& name, int time_factor) {
  CandidateRun run;
  try {
    SceneSimulation simulation(parse_scene(scene_json, base_dir, name));
    const TetMesh& mesh = simulation.problem().mesh;
    run.tets = mesh.num_tets();
    const double blowup = FlutterThresholds{}.blowup_displacement(mesh.rest);
    std::vector<double> step_ms;
    const SimulationResult result = simulation.run([&](const StepState& s) {
      step_ms.push_back(s.phase_ms.at("step"));
      if (!s.displacement.allFinite() || s.displacement.cwiseAbs().maxCoeff() > blowup)
        throw NumericalFault("unstable: the displacement left 100x the body's diagonal at step " +
                             std::to_string(s.step));
    });
    if (!result.converged) {
      run.failure = "did not converge: " + result.message;
      return run;
    }
    if (!result.displacement.allFinite()) {
      run.failure = "non-finite displacement";
      return run;
    }
    const bool dynamic = simulation.scene().analysis.type == AnalysisType::Dynamic;
    if (dynamic && !step_ms.empty()) {
      const int warmup = std::min<int>(2, static_cast<int>(step_ms.size()) - 1);
      run.ms_per_step = median(std::vector<double>(step_ms.begin() + warmup, step_ms.end()));
      run.cost_ms = run.ms_per_step / time_factor;
      run.linear_iterations_per_step =
          static_cast<double>(result.linear_iterations) / std::max(result.steps, 1);
    } else {
      run.ms_per_step = result.timings_ms.at("total");
      run.cost_ms = run.ms_per_step;
      run.linear_iterations_per_step = result.linear_iterations;
    }
    run.state = {mesh, result.displacement};
    run.completed = true;
  } catch (const std::exception& e) {
    run.failure = e.what();
  }
  return run;
}

}  // namespace corofem
