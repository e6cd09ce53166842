#include "report/paper_tables.hpp"

#include <algorithm>
#include <cstring>
#include <ostream>

#include "core/errors.hpp"
#include "core/machine_roofs.hpp"
#include "core/threads.hpp"
#include "report/case_record.hpp"
#include "report/timed_run.hpp"

namespace corofem {
using nlohmann::json;

json paper_table1_row(const std::string& m) {
  // PAPER_NOTES section 6 (Core 2 Duo 6600, 2.4 GHz, one thread).
  if (m == "bunny")
    return {{"tets", 11241},          {"vertices", 2918},  {"levels", 3},
            {"rotate_ms", 21},        {"assemble_ms", 18}, {"update_ms", 11},
            {"update_naive_ms", 108}, {"solve_ms", 10},    {"tps", 17}};
  if (m == "horse")
    return {{"tets", 33689},          {"vertices", 8632},  {"levels", 4},
            {"rotate_ms", 67},        {"assemble_ms", 58}, {"update_ms", 39},
            {"update_naive_ms", 354}, {"solve_ms", 26},    {"tps", 5.2}};
  if (m == "dragon")
    return {{"tets", 67309},           {"vertices", 16943},  {"levels", 4},
            {"rotate_ms", 112},        {"assemble_ms", 103}, {"update_ms", 94},
            {"update_naive_ms", 1183}, {"solve_ms", 51},     {"tps", 2.8}};
  return nullptr;
}

json paper_table2_tps(const std::string& m) {
  if (m == "bunny") return 31;
  if (m == "horse") return 10.1;
  if (m == "dragon") return 5.0;
  return nullptr;
}

namespace {

double tps_of(const TimedRun& run, int warmup) {
  return 1000.0 / run.median_ms("step", warmup);
}

/// Median ms of every phase of a step, the step and its time steps per second.
json phase_medians(const TimedRun& run, int warmup) {
  json phases;
  for (const char* phase :
       {"checks", "rotate", "assemble", "forces", "system", "update", "solve", "step"})
    phases[phase] = run.median_ms(phase, warmup);
  phases["tps"] = tps_of(run, warmup);
  return phases;
}

/// The phase a multigrid run's coarsest factorizations were timed in: "solve" when the solver
/// deferred them to its solves (MultigridSolver::defers_update), else "update".
json coarsest_factorization_phase(const TimedRun& run) {
  if (!run.multigrid.is_object()) return nullptr;
  return run.multigrid.value("deferred_updates", 0) > 0 ? "solve" : "update";
}

/// One row of the multigrid quality table: the hierarchy of `pcg` (an MG-PCG run) and its
/// iterations and times, with the convergence factor of the stationary V(1,1) cycle (`vcycle`,
/// the same scene solved by V-cycles to the same tolerance).
json multigrid_quality_row(const TimedRun& pcg, const TimedRun& vcycle, int warmup) {
  const json& mg = pcg.multigrid;
  json sizes = json::array();
  for (const json& level : mg["levels"]) sizes.push_back(level["vertices"]);
  double setup = 0;
  for (auto& [phase, ms] : mg["setup_ms"].items()) setup += ms.get<double>();
  return {{"hierarchy", mg["hierarchy"]},
          {"levels", sizes.size()},
          {"level_vertices", sizes},
          {"operator_complexity", mg["operator_complexity"]},
          {"rho", vcycle.multigrid["rho"]},
          {"vcycles", vcycle.multigrid["iterations"]},
          {"mgpcg_iterations", mg["iterations"]},
          {"setup_ms", setup},
          {"setup_phases_ms", mg["setup_ms"]},
          {"update_ms", pcg.median_ms("update", warmup)},
          {"solve_ms", pcg.median_ms("solve", warmup)},
          {"solve_parts_ms", mg["solve_parts_ms"]},  // means over the run's solves
          {"update_parts_ms", mg["update_parts_ms"]},
          {"vcycle_solve_ms", vcycle.median_ms("solve", warmup)},
          {"step_ms", pcg.median_ms("step", warmup)},
          {"coarsest_factorization_in", coarsest_factorization_phase(pcg)}};
}

}  // namespace

json run_paper_tables(const ReportConfig& config) {
  json tables = {{"table1", json::array()},       {"table2", json::array()},
                 {"small_strain", json::array()}, {"jacobi_pcg", json::array()},
                 {"verification", json::array()}, {"multigrid", json::array()},
                 {"rival_solvers", json::array()}};
  const int warmup = config.table_warmup(), measured = config.table_measured();
  const int steps = warmup + measured;
  tables["settings"] = {
      {"warmup_steps", warmup},
      {"measured_steps", measured},
      {"statistic", "median over the measured steps"},
      {"rotation", "energy-newton"},
      {"solver", "mgpcg"},
      {"accuracy", "MG-PCG to relative residual " + std::to_string(config.default_tolerance()) +
                       " per step, warm-started from the previous velocity"},
      {"tolerance", config.default_tolerance()},
      {"dt", 0.01},
      {"oracle_check_steps", nlohmann::json::array()}};
  // The rooflines' roofs, this machine's, measured before the runs at the run's thread count
  // and at one thread (Table 1 is measured at both).
  const int threads = thread_count();
  const MachineRoofs roofs{measure_stream_triad_gbps(), measure_dense_gflops()};
  MachineRoofs roofs_one = roofs;
  if (threads > 1) {
    const ScopedThreadCount one(1);
    roofs_one = {measure_stream_triad_gbps(), measure_dense_gflops()};
  }
  tables["threads"] = threads;
  tables["stream_triad_GBps"] = roofs.stream_gbps;
  tables["dense_gflops"] = roofs.dense_gflops;
  tables["one_thread_roofs"] = {{"stream_triad_GBps", roofs_one.stream_gbps},
                                {"dense_gflops", roofs_one.dense_gflops}};
  std::vector<int> check_steps{warmup + 1, warmup + measured / 2, steps};
  check_steps.erase(std::unique(check_steps.begin(), check_steps.end()), check_steps.end());
  tables["settings"]["oracle_check_steps"] = check_steps;
  for (const std::string& model : config.models()) {
    for (SceneSize size : config.table_sizes(model)) {
      const std::string id = model + "-" + size_name(size);
      // The paper's row sits beside ours only at the paper's size (not beside quick runs).
      const std::string paper_model = config.with_models()
                                          ? (size == file_model_size(model) ? model : "")
                                          : paper_model_of(size);
      const json scene =
          table_scene(model, size, steps, config.default_tolerance(), config.models_dir);
      auto say = [&](const std::string& what) {
        if (config.progress)
          *config.progress << "report: tables: " << id << ": " << what << std::endl;
      };
      json base = {{"model", id}, {"scene", scene}, {"paper_model", paper_model}};
      // Table 1: the paper's method.
      TimedRun main;
      say("energy-newton + MG-PCG");
      json row = record_case(base, [&] {
        TimedRunOptions options;
        options.warmup_steps = warmup;
        options.check_steps = check_steps;
        options.check_operators = true;
        TimedRunOptions with_matptap = options;  // MatPtAP timed once, after the main run
        with_matptap.time_matptap = true;
        main = timed_run(scene, id, with_matptap);
        // The same run on one thread (the paper's setting), unless this one is.
        json one_thread = nullptr;
        TimedRun single_run;
        if (threads > 1) {
          say("energy-newton + MG-PCG on one thread");
          const ScopedThreadCount one(1);
          single_run = timed_run(scene, id, options);
          one_thread = phase_medians(single_run, warmup);
          one_thread["roofline"] = single_run.roofline(warmup, roofs_one);
          one_thread["separate_run"] = true;
          one_thread["linear_iterations"] = single_run.result.linear_iterations;
          // Every kernel gives the same bits at every thread count: so must the whole run.
          const Eigen::VectorXd& u1 = single_run.result.displacement;
          const Eigen::VectorXd& u = main.result.displacement;
          one_thread["same_displacement_bits"] =
              u1.size() == u.size() &&
              std::memcmp(u1.data(), u.data(), u.size() * sizeof(double)) == 0;
        }
        say("naive Galerkin update");
        const TimedRun naive = timed_run(with_analysis(scene, {{"galerkin", "naive"}}), id, {});
        say("CHOLMOD step");
        const TimedRun cholmod = timed_run(with_analysis(scene, {{"solver", "cholmod"}}), id, {});
        json all = phase_medians(main, warmup);
        // Our Galerkin update (the scene's method) against PETSc's MatPtAP (numeric reuse, one
        // thread) on the same matrices.
        const auto galerkin_ms = [](const TimedRun& run) -> json {
          if (!run.multigrid.is_object() || !run.multigrid.contains("update_parts_ms"))
            return nullptr;
          return run.multigrid["update_parts_ms"].value("galerkin", 0.0);
        };
        json ours_one = threads > 1 ? galerkin_ms(single_run) : galerkin_ms(main);
        json matptap = nullptr;
        if (main.matptap_ms >= 0)
          matptap = {
              {"matptap_ms", main.matptap_ms},
              {"galerkin", main.multigrid.value("params", json::object()).value("galerkin", "")},
              {"galerkin_ms", galerkin_ms(main)},
              {"galerkin_one_thread_ms", ours_one},
              {"matptap_over_galerkin_one_thread",
               ours_one.is_number() && ours_one.get<double>() > 0
                   ? json(main.matptap_ms / ours_one.get<double>())
                   : json(nullptr)}};
        if (one_thread.is_null()) {  // this run is on one thread
          one_thread = all;
          one_thread["roofline"] = main.roofline(warmup, roofs_one);
          one_thread["separate_run"] = false;
          one_thread["linear_iterations"] = main.result.linear_iterations;
          one_thread["same_displacement_bits"] = true;
        }
        return json{{"tets", main.tets},
                    {"threads", threads},
                    {"phases_ms", all},
                    {"one_thread", one_thread},
                    {"vertices", main.vertices},
                    {"levels", main.levels},
                    {"rotate_ms", main.median_ms("rotate", warmup)},
                    {"assemble_ms", main.median_ms("assemble", warmup)},
                    {"update_ms", main.median_ms("update", warmup)},
                    {"update_naive_ms", naive.median_ms("update", warmup)},
                    {"coarsest_factorization_in", coarsest_factorization_phase(main)},
                    {"solve_ms", main.median_ms("solve", warmup)},
                    {"step_ms", main.median_ms("step", warmup)},
                    {"tps", tps_of(main, warmup)},
                    {"solve_iterations", main.median_iterations(warmup)},
                    {"linear_iterations", main.result.linear_iterations},
                    {"solve_accuracy",
                     {{"relative_residual_max", main.solve_residual_max},
                      {"error_vs_cholmod_max", main.solve_error_max},
                      {"checked_steps", check_steps}}},
                    {"cholmod_step_ms", cholmod.median_ms("step", warmup)},
                    {"cholmod_factorize_ms", cholmod.median_ms("update", warmup)},
                    {"speedup_vs_cholmod",
                     cholmod.median_ms("step", warmup) / main.median_ms("step", warmup)},
                    {"inverted_max", main.result.inverted_max},
                    {"roofline", main.roofline(warmup, roofs)},
                    {"galerkin_vs_matptap", matptap},
                    {"paper", paper_table1_row(paper_model)}};
      });
      tables["table1"].push_back(row);
      if (row["completed"]) {
        tables["verification"].push_back(
            {{"model", id},
             {"checks",
              {{{"oracle", "CHOLMOD solve of the same step"},
                {"quantity", "relative error of the MG-PCG solution"},
                {"largest", main.solve_error_max},
                {"count", check_steps.size()}},
               {{"oracle", "Eigen sparse R A R^T"},
                {"quantity", "relative Frobenius error of every coarse level"},
                {"largest", main.galerkin_error_max},
                {"count", main.levels - 1}},
               {{"oracle", "energy-exact (closed-form minimizer)"},
                {"quantity", "energy-newton rotation angle error (rad)"},
                {"largest", main.rotation_error_max_rad},
                {"count", main.rotation_elements_compared}}}}});
      }
      // Table 2: polar decomposition with spatial smoothing.
      say("polar + smoothing");
      tables["table2"].push_back(record_case({{"model", id}, {"paper_model", paper_model}}, [&] {
        const TimedRun polar =
            timed_run(with_analysis(scene, {{"rotation", "polar-smoothed"}}), id, {});
        return json{{"tets", polar.tets},
                    {"tps", tps_of(polar, warmup)},
                    {"rotate_ms", polar.median_ms("rotate", warmup)},
                    {"paper_tps", paper_table2_tps(paper_model)}};
      }));
      // Figure 1: small strain against corotated.
      say("small strain");
      tables["small_strain"].push_back(record_case({{"model", id}}, [&] {
        const TimedRun linear =
            timed_run(with_analysis(scene, {{"formulation", "linear"}}), id, {});
        if (!row["completed"]) throw NumericalFault("the corotated run of this model failed");
        return json{{"tps", tps_of(linear, warmup)},
                    {"corotated_tps", tps_of(main, warmup)},
                    {"volume_change", linear.final_volume / linear.rest_volume - 1},
                    {"corotated_volume_change", main.final_volume / main.rest_volume - 1}};
      }));
      // Multigrid quality: the paper's re-meshed hierarchy against the covering lattice.
      for (const char* hierarchy : {"meshes", "lattice"}) {
        say(std::string("multigrid quality: ") + hierarchy);
        tables["multigrid"].push_back(record_case({{"model", id}}, [&] {
          const json on = with_analysis(scene, {{"hierarchy", hierarchy}});
          const std::string kind =
              main.multigrid.is_null() ? "" : main.multigrid.value("hierarchy", "");
          const TimedRun pcg = kind == hierarchy ? main : timed_run(on, id, {});
          const TimedRun vcycle =
              timed_run(with_analysis(on, {{"solver", "multigrid"}, {"vcycles", 0}}), id, {});
          return multigrid_quality_row(pcg, vcycle, warmup);
        }));
      }
      // The baseline preconditioner at the same accuracy, on the scene and on the scene 100x
      // stiffer: M + dt^2 K is mass-dominated at the paper's soft materials (Jacobi's CG
      // iterations grow as sqrt(cond), the V-cycle's barely), so the comparison says where each
      // wins.
      for (const double young_scale : {1.0, 100.0}) {
        say("Jacobi-PCG" + std::string(young_scale > 1 ? ", 100x stiffer" : ""));
        tables["jacobi_pcg"].push_back(
            record_case({{"model", id}, {"young_scale", young_scale}}, [&] {
              const json stiffer = with_young_scaled(scene, young_scale);
              const TimedRun jacobi =
                  timed_run(with_analysis(stiffer, {{"solver", "jacobi-pcg"}}), id, {});
              const TimedRun mgpcg = young_scale == 1.0 ? main : timed_run(stiffer, id, {});
              return json{
                  {"step_ms", jacobi.median_ms("step", warmup)},
                  {"solve_ms", jacobi.median_ms("solve", warmup)},
                  {"iterations", jacobi.median_iterations(warmup)},
                  {"mgpcg_step_ms",
                   mgpcg.step_ms.empty() ? json(nullptr) : json(mgpcg.median_ms("step", warmup))},
                  {"mgpcg_iterations",
                   mgpcg.step_ms.empty() ? json(nullptr) : json(mgpcg.median_iterations(warmup))}};
            }));
      }
      // The algebraic multigrid users would pick instead, to the same tolerance, their setup
      // timed as the update phase (a new matrix every step), as ours is; the AMGs also with
      // their setup reused across steps (GAMG's interpolation, BoomerAMG's whole hierarchy).
      const std::vector<std::pair<std::string, bool>> rivals = {{"petsc-gamg", false},
                                                                {"hypre-boomeramg", false},
                                                                {"petsc-mg", false},
                                                                {"petsc-gamg", true},
                                                                {"hypre-boomeramg", true}};
      for (const auto& [rival, reuse] : rivals) {
        say(rival + (reuse ? " (setup reuse)" : ""));
        tables["rival_solvers"].push_back(
            record_case({{"model", id}, {"solver", rival}, {"setup_reuse", reuse}}, [&] {
              const TimedRun run = timed_run(
                  with_analysis(scene, {{"solver", rival}, {"setup_reuse", reuse}}), id, {});
              const double mgpcg_step = main.step_ms.empty() ? 0.0 : main.median_ms("step", warmup);
              return json{
                  {"step_ms", run.median_ms("step", warmup)},
                  {"update_ms", run.median_ms("update", warmup)},
                  {"solve_ms", run.median_ms("solve", warmup)},
                  {"iterations", run.median_iterations(warmup)},
                  {"mgpcg_step_ms", mgpcg_step > 0 ? json(mgpcg_step) : json(nullptr)},
                  {"mgpcg_update_ms",
                   main.step_ms.empty() ? json(nullptr) : json(main.median_ms("update", warmup))},
                  {"mgpcg_solve_ms",
                   main.step_ms.empty() ? json(nullptr) : json(main.median_ms("solve", warmup))},
                  {"step_over_mgpcg", mgpcg_step > 0
                                          ? json(run.median_ms("step", warmup) / mgpcg_step)
                                          : json(nullptr)}};
            }));
      }
    }
  }
  return tables;
}

}  // namespace corofem
