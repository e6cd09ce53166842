#include "report/paper_tables.hpp"

#include <algorithm>
#include <cstring>
#include <ostream>

#include "core/errors.hpp"
#include "core/machine_roofs.hpp"
#include "core/number_text.hpp"
#include "core/threads.hpp"
#include "io/solver_record.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "report/analysis_variant.hpp"
#include "report/case_record.hpp"
#include "report/report_checkpoint.hpp"
#include "report/section_progress.hpp"
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
  if (!run.multigrid) return nullptr;
  return run.multigrid->deferred_updates > 0 ? "solve" : "update";
}

/// A run's multigrid summary; NumericalFault where the run has none (its solver is another).
const MultigridSummary& multigrid_of(const TimedRun& run) {
  if (!run.multigrid) throw NumericalFault("the run has no multigrid solver to describe");
  return *run.multigrid;
}

/// One row of the multigrid quality table: the hierarchy of `pcg` (an MG-PCG run) and its
/// iterations and times, with the convergence factor of the stationary V(1,1) cycle (`vcycle`,
/// the same scene solved by V-cycles to the same tolerance).
json multigrid_quality_row(const TimedRun& pcg, const TimedRun& vcycle, int warmup) {
  const MultigridSummary& mg = multigrid_of(pcg);
  const MultigridSummary& cycles = multigrid_of(vcycle);
  json sizes = json::array();
  for (const MultigridLevelSummary& level : mg.levels) sizes.push_back(level.vertices);
  const MultigridSetupParts& setup = mg.setup;
  return {{"hierarchy", kHierarchyKinds.name(mg.params.hierarchy.kind)},
          {"tets", pcg.tets},
          {"levels", sizes.size()},
          {"level_vertices", sizes},
          {"operator_complexity", mg.operator_complexity},
          {"rho", to_json(cycles.rho)},
          {"vcycles", to_json(cycles.iterations)},
          {"mgpcg_iterations", to_json(mg.iterations)},
          {"setup_ms", setup.transfers + setup.galerkin_streams + setup.coarse_meshes.value_or(0)},
          {"setup_phases_ms", to_json(setup)},
          {"update_ms", pcg.median_ms("update", warmup)},
          {"solve_ms", pcg.median_ms("solve", warmup)},
          {"solve_parts_ms", to_json(mg.solve)},  // means over the run's solves
          {"update_parts_ms", to_json(mg.update)},
          {"vcycle_solve_ms", vcycle.median_ms("solve", warmup)},
          {"step_ms", pcg.median_ms("step", warmup)},
          {"coarsest_factorization_in", coarsest_factorization_phase(pcg)}};
}

/// What every table of one model shares: its scene and names, the step counts, and the main run
/// (the paper's method, energy-newton + MG-PCG), which several tables compare against.
struct ModelTables {
  std::string id, paper_model;
  json scene;
  int warmup = 0;
  int cholmod_measured = 0;  ///< measured steps of the CHOLMOD row
  std::vector<int> check_steps;
  MachineRoofs roofs, roofs_one;  ///< at the run's thread count and at one thread
  std::ostream* progress = nullptr;
  std::string progress_prefix;  ///< "report: tables 2/5: quadruped-34k (about 3 min left)"
  TimedRun main;
  bool main_completed = false;

  void say(const std::string& what) const {
    if (progress) *progress << progress_prefix << ": " << what << std::endl;
  }
  double main_median_ms(const char* phase) const { return main.median_ms(phase, warmup); }
};

/// The one-thread columns of Table 1: a run of their own at two or more threads, which must
/// give the all-thread run's bits; the main run itself at one.
json one_thread_columns(const ModelTables& m, const TimedRun& single_run, bool separate) {
  const TimedRun& run = separate ? single_run : m.main;
  json one = phase_medians(run, m.warmup);
  one["roofline"] = run.roofline(m.warmup, m.roofs_one);
  one["samples_ms"] = run.samples_ms(m.warmup);
  one["separate_run"] = separate;
  one["linear_iterations"] = run.result.linear_iterations;
  // Every kernel gives the same bits at every thread count: so must the whole run.
  const Eigen::VectorXd& u1 = run.result.displacement;
  const Eigen::VectorXd& u = m.main.result.displacement;
  one["same_displacement_bits"] =
      u1.size() == u.size() && std::memcmp(u1.data(), u.data(), u.size() * sizeof(double)) == 0;
  return one;
}

/// Our Galerkin update (the scene's method) against PETSc's MatPtAP (numeric reuse, one thread)
/// on the same matrices; null where PETSc did not run.
json galerkin_vs_matptap(const TimedRun& main, const TimedRun& one_thread_run) {
  const auto galerkin_ms = [](const TimedRun& run) -> json {
    return run.multigrid ? json(run.multigrid->update.galerkin) : json(nullptr);
  };
  if (main.matptap_ms < 0) return nullptr;
  const json ours_one = galerkin_ms(one_thread_run);
  return {
      {"matptap_ms", main.matptap_ms},
      {"galerkin", main.multigrid ? kGalerkinMethods.name(main.multigrid->params.galerkin) : ""},
      {"galerkin_ms", galerkin_ms(main)},
      {"galerkin_one_thread_ms", ours_one},
      {"matptap_over_galerkin_one_thread", ours_one.is_number() && ours_one.get<double>() > 0
                                               ? json(main.matptap_ms / ours_one.get<double>())
                                               : json(nullptr)}};
}

/// Table 1: the paper's method, its phases at the run's thread count and at one thread, the naive
/// Galerkin update and CHOLMOD beside it; sets m.main.
json table1_row(ModelTables& m, int threads) {
  m.say("energy-newton + MG-PCG");
  json row =
      record_case({{"model", m.id}, {"scene", m.scene}, {"paper_model", m.paper_model}}, [&] {
        TimedRunOptions checked;  // the oracles run once, on the main run; MatPtAP timed after it
        checked.warmup_steps = m.warmup;
        checked.check_steps = m.check_steps;
        checked.check_operators = true;
        checked.time_matptap = true;
        m.main = timed_run(m.scene, m.id, checked);
        // The same run on one thread (the paper's setting), unless this one is. It must give the
        // main run's bits (one_thread_columns checks), so the oracles would only repeat what they
        // found: on quadruped-67k they were most of its time.
        TimedRun single_run;
        if (threads > 1) {
          m.say("energy-newton + MG-PCG on one thread");
          const ScopedThreadCount one(1);
          TimedRunOptions unchecked;
          unchecked.warmup_steps = m.warmup;
          single_run = timed_run(m.scene, m.id, unchecked);
        }
        m.say("naive Galerkin update");
        const TimedRun naive =
            timed_run(with_analysis(m.scene, {.galerkin = GalerkinMethod::Naive}), m.id, {});
        m.say("CHOLMOD step");
        json cholmod_scene = m.scene;  // ReportConfig::table_cholmod_measured
        cholmod_scene["analysis"]["steps"] = m.warmup + m.cholmod_measured;
        const TimedRun cholmod =
            timed_run(with_analysis(cholmod_scene, {.solver = SolverKind::Cholmod}), m.id, {});
        const TimedRun& main = m.main;
        return json{
            {"tets", main.tets},
            {"threads", threads},
            {"phases_ms", phase_medians(main, m.warmup)},
            {"samples_ms", main.samples_ms(m.warmup)},
            {"one_thread", one_thread_columns(m, single_run, threads > 1)},
            {"vertices", main.vertices},
            {"levels", main.levels},
            {"rotate_ms", m.main_median_ms("rotate")},
            {"assemble_ms", m.main_median_ms("assemble")},
            {"update_ms", m.main_median_ms("update")},
            {"update_naive_ms", naive.median_ms("update", m.warmup)},
            {"coarsest_factorization_in", coarsest_factorization_phase(main)},
            {"solve_ms", m.main_median_ms("solve")},
            {"step_ms", m.main_median_ms("step")},
            {"tps", tps_of(main, m.warmup)},
            {"solve_iterations", main.median_iterations(m.warmup)},
            {"linear_iterations", main.result.linear_iterations},
            {"solve_accuracy",
             {{"relative_residual_max", main.solve_residual_max},
              {"error_vs_cholmod_max", main.solve_error_max},
              {"checked_steps", m.check_steps}}},
            {"cholmod_step_ms", cholmod.median_ms("step", m.warmup)},
            {"cholmod_factorize_ms", cholmod.median_ms("update", m.warmup)},
            {"speedup_vs_cholmod", cholmod.median_ms("step", m.warmup) / m.main_median_ms("step")},
            {"inverted_max", main.result.inverted_max},
            {"roofline", main.roofline(m.warmup, m.roofs)},
            {"galerkin_vs_matptap", galerkin_vs_matptap(main, threads > 1 ? single_run : main)},
            {"paper", paper_table1_row(m.paper_model)}};
      });
  m.main_completed = row["completed"].get<bool>();
  return row;
}

/// The verification summary: the main run's oracle checks.
json verification_row(const ModelTables& m) {
  const TimedRun& main = m.main;
  return {{"model", m.id},
          {"checks",
           {{{"oracle", "CHOLMOD solve of the same step"},
             {"quantity", "relative error of the MG-PCG solution"},
             {"largest", main.solve_error_max},
             {"count", m.check_steps.size()}},
            {{"oracle", "Eigen sparse R A R^T"},
             {"quantity", "relative Frobenius error of every coarse level"},
             {"largest", main.galerkin_error_max},
             {"count", main.levels - 1}},
            {{"oracle", "energy-exact (closed-form minimizer)"},
             {"quantity", "energy-newton rotation angle error (rad)"},
             {"largest", main.rotation_error_max_rad},
             {"count", main.rotation_elements_compared}}}}};
}

/// Table 2: polar decomposition with spatial smoothing.
json table2_row(const ModelTables& m) {
  m.say("polar + smoothing");
  return record_case({{"model", m.id}, {"paper_model", m.paper_model}}, [&] {
    const TimedRun polar =
        timed_run(with_analysis(m.scene, {.rotation = RotationMethod::PolarSmoothed}), m.id, {});
    return json{{"tets", polar.tets},
                {"tps", tps_of(polar, m.warmup)},
                {"rotate_ms", polar.median_ms("rotate", m.warmup)},
                {"paper_tps", paper_table2_tps(m.paper_model)}};
  });
}

/// Figure 1: small strain against corotated.
json small_strain_row(const ModelTables& m) {
  m.say("small strain");
  return record_case({{"model", m.id}}, [&] {
    const TimedRun linear =
        timed_run(with_analysis(m.scene, {.formulation = Formulation::Linear}), m.id, {});
    if (!m.main_completed) throw NumericalFault("the corotated run of this model failed");
    return json{{"tps", tps_of(linear, m.warmup)},
                {"corotated_tps", tps_of(m.main, m.warmup)},
                {"volume_change", linear.final_volume / linear.rest_volume - 1},
                {"corotated_volume_change", m.main.final_volume / m.main.rest_volume - 1}};
  });
}

/// Whether the scene's mesh comes with its coarse levels (the models' L1, L2).
bool has_given_levels(const json& scene) {
  return scene["mesh"].contains("levels");
}

/// The scene as a user's bare surface gives it: the fine surface only, the coarse levels derived
/// from it (scene/coarse_meshes.hpp).
json bare_surface(json scene) {
  scene["mesh"].erase("levels");
  return scene;
}

/// The vertex ratio per level at which the quadruped's rho and MG-PCG iterations stop depending
/// on its size (lib/docs/multigrid.md: rho and iterations flat from 11k to 270k tets).
constexpr double kSizeIndependentCoarsening = 3.5;

/// Multigrid quality: the paper's re-meshed hierarchy (its levels as given, or `bare`: derived
/// from the fine surface alone; `coarsening`: derived at that vertex ratio per level) or the
/// covering lattice.
json multigrid_row(const ModelTables& m, HierarchyKind hierarchy, bool bare = false,
                   std::optional<double> coarsening = std::nullopt) {
  const std::string name = kHierarchyKinds.name(hierarchy);
  m.say("multigrid quality: " + name + (bare ? ", bare surface" : "") +
        (coarsening ? ", " + general_number(*coarsening) + "x fewer vertices per level" : ""));
  return record_case({{"model", m.id}}, [&] {
    const json on = with_analysis(bare ? bare_surface(m.scene) : m.scene,
                                  {.hierarchy = hierarchy, .coarsening = coarsening});
    const bool main_is_it =
        !coarsening && m.main.multigrid && m.main.multigrid->params.hierarchy.kind == hierarchy;
    const TimedRun pcg = main_is_it && !bare ? m.main : timed_run(on, m.id, {});
    const TimedRun vcycle =
        timed_run(with_analysis(on, {.solver = SolverKind::Multigrid, .vcycles = 0}), m.id, {});
    json row = multigrid_quality_row(pcg, vcycle, m.warmup);
    if (coarsening) row["coarsening"] = *coarsening;
    if (hierarchy == HierarchyKind::Meshes)
      row["coarse_meshes"] = bare                        ? "derived from the bare surface"
                             : has_given_levels(m.scene) ? "given"
                                                         : "derived";
    return row;
  });
}

/// The textbook property the paper claims for its hierarchy: rho and MG-PCG iterations that do
/// not grow with the mesh. `model`'s re-meshed rows at each of its sizes, and their spreads
/// against the targets of size independence (rho within 0.05, iterations within 1); null below
/// two sizes. The
/// rows of one `coarsening` (0: the default size doubling).
json size_independence(const json& multigrid_rows, const std::string& model, double coarsening) {
  json sizes = json::array();
  double rho_lo = 1e300, rho_hi = -1e300, it_lo = 1e300, it_hi = -1e300;
  for (const json& r : multigrid_rows) {
    if (!r.value("completed", false) || r.value("hierarchy", "") != "meshes" ||
        r.value("coarse_meshes", "") != "derived" ||
        r["model"].get<std::string>().rfind(model + "-", 0) != 0 ||
        r.value("coarsening", 0.0) != coarsening)
      continue;
    const double rho = r["rho"].get<double>(), iterations = r["mgpcg_iterations"].get<double>();
    sizes.push_back({{"model", r["model"]},
                     {"tets", r["tets"]},
                     {"rho", rho},
                     {"mgpcg_iterations", iterations}});
    rho_lo = std::min(rho_lo, rho);
    rho_hi = std::max(rho_hi, rho);
    it_lo = std::min(it_lo, iterations);
    it_hi = std::max(it_hi, iterations);
  }
  if (sizes.size() < 2) return nullptr;
  return {{"model", model},
          {"coarsening", coarsening},
          {"sizes", sizes},
          {"rho_spread", rho_hi - rho_lo},
          {"iterations_spread", it_hi - it_lo},
          {"targets", {{"rho_spread", 0.05}, {"iterations_spread", 1}}}};
}

/// The baseline preconditioner at the same accuracy, on the scene and on the scene 100x stiffer:
/// M + dt^2 K is mass-dominated at the paper's soft materials (Jacobi's CG iterations grow as
/// sqrt(cond), the V-cycle's barely), so the comparison says where each wins.
json jacobi_row(const ModelTables& m, double young_scale) {
  m.say("Jacobi-PCG" + std::string(young_scale > 1 ? ", 100x stiffer" : ""));
  return record_case({{"model", m.id}, {"young_scale", young_scale}}, [&] {
    const json stiffer = with_young_scaled(m.scene, young_scale);
    const TimedRun jacobi =
        timed_run(with_analysis(stiffer, {.solver = SolverKind::JacobiPcg}), m.id, {});
    const TimedRun mgpcg = young_scale == 1.0 ? m.main : timed_run(stiffer, m.id, {});
    const bool ran = !mgpcg.step_ms.empty();
    json row = {
        {"step_ms", jacobi.median_ms("step", m.warmup)},
        {"solve_ms", jacobi.median_ms("solve", m.warmup)},
        {"iterations", jacobi.median_iterations(m.warmup)},
        {"mgpcg_step_ms", ran ? json(mgpcg.median_ms("step", m.warmup)) : json(nullptr)},
        {"mgpcg_iterations", ran ? json(mgpcg.median_iterations(m.warmup)) : json(nullptr)}};
    if (has_given_levels(m.scene)) {  // and as a user's bare surface would run it
      const TimedRun bare = timed_run(bare_surface(stiffer), m.id, {});
      row["bare_surface_mgpcg_step_ms"] = bare.median_ms("step", m.warmup);
      row["bare_surface_mgpcg_iterations"] = bare.median_iterations(m.warmup);
    }
    return row;
  });
}

/// An algebraic multigrid users would pick instead, to the same tolerance, its setup timed as the
/// update phase (a new matrix every step), as ours is; or with its setup reused across steps
/// (GAMG's interpolation, BoomerAMG's whole hierarchy).
json rival_row(const ModelTables& m, SolverKind rival, bool reuse) {
  const std::string name = rival.name();
  m.say(name + (reuse ? " (setup reuse)" : ""));
  return record_case({{"model", m.id}, {"solver", name}, {"setup_reuse", reuse}}, [&] {
    const TimedRun run =
        timed_run(with_analysis(m.scene, {.solver = rival, .setup_reuse = reuse}), m.id, {});
    const bool ran = !m.main.step_ms.empty();
    const double mgpcg_step = ran ? m.main_median_ms("step") : 0.0;
    return json{
        {"step_ms", run.median_ms("step", m.warmup)},
        {"update_ms", run.median_ms("update", m.warmup)},
        {"solve_ms", run.median_ms("solve", m.warmup)},
        {"iterations", run.median_iterations(m.warmup)},
        {"mgpcg_step_ms", mgpcg_step > 0 ? json(mgpcg_step) : json(nullptr)},
        {"mgpcg_update_ms", ran ? json(m.main_median_ms("update")) : json(nullptr)},
        {"mgpcg_solve_ms", ran ? json(m.main_median_ms("solve")) : json(nullptr)},
        {"step_over_mgpcg",
         mgpcg_step > 0 ? json(run.median_ms("step", m.warmup) / mgpcg_step) : json(nullptr)}};
  });
}

json table_settings(const ReportConfig& config, int warmup, int measured,
                    const std::vector<int>& check_steps) {
  return {{"warmup_steps", warmup},
          {"measured_steps", measured},
          {"measured_steps_cholmod_row", config.table_cholmod_measured()},
          {"statistic", "median over the measured steps"},
          {"rotation", "energy-newton"},
          {"solver", "mgpcg"},
          {"galerkin", kGalerkinMethods.name(MultigridParams{}.galerkin)},
          {"accuracy", "MG-PCG to relative residual " + general_number(config.default_tolerance()) +
                           " per step, warm-started from the previous velocity"},
          {"tolerance", config.default_tolerance()},
          {"dt", 0.01},
          {"oracle_check_steps", check_steps}};
}

/// Every table's rows of one model at one of Table 1's sizes.
void add_model_rows(json& tables, ModelTables& m, const std::string& model, SceneSize size,
                    const ReportConfig& config, int threads) {
  tables["table1"].push_back(table1_row(m, threads));
  if (m.main_completed) tables["verification"].push_back(verification_row(m));
  tables["table2"].push_back(table2_row(m));
  tables["small_strain"].push_back(small_strain_row(m));
  for (const HierarchyKind hierarchy : {HierarchyKind::Meshes, HierarchyKind::Lattice})
    tables["multigrid"].push_back(multigrid_row(m, hierarchy));
  if (model == "quadruped")  // its coarse meshes derived, at sizes corofem picks
    tables["multigrid"].push_back(
        multigrid_row(m, HierarchyKind::Meshes, false, kSizeIndependentCoarsening));
  if (has_given_levels(m.scene))
    tables["multigrid"].push_back(multigrid_row(m, HierarchyKind::Meshes, true));
  if (config.jacobi_table(size))
    for (const double young_scale : {1.0, 100.0})
      tables["jacobi_pcg"].push_back(jacobi_row(m, young_scale));
  if (!config.comparison_tables(size)) return;
  for (const auto& [rival, reuse] :
       std::vector<std::pair<SolverKind, bool>>{{SolverKind::PetscGamg, false},
                                                {SolverKind::HypreBoomeramg, false},
                                                {SolverKind::PetscMg, false},
                                                {SolverKind::PetscGamg, true},
                                                {SolverKind::HypreBoomeramg, true}})
    tables["rival_solvers"].push_back(rival_row(m, rival, reuse));
}

}  // namespace

json run_paper_tables(const ReportConfig& config) {
  json tables = {{"table1", json::array()},       {"table2", json::array()},
                 {"small_strain", json::array()}, {"jacobi_pcg", json::array()},
                 {"verification", json::array()}, {"multigrid", json::array()},
                 {"rival_solvers", json::array()}};
  const int warmup = config.table_warmup(), measured = config.table_measured();
  const int steps = warmup + measured;
  std::vector<int> check_steps{warmup + 1, warmup + measured / 2, steps};
  check_steps.erase(std::unique(check_steps.begin(), check_steps.end()), check_steps.end());
  tables["settings"] = table_settings(config, warmup, measured, check_steps);
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
  int units = 0;
  for (const std::string& model : config.models())
    units += static_cast<int>(config.table_sizes(model).size() +
                              config.multigrid_only_sizes(model).size());
  SectionProgress progress(config.progress, "tables", units);
  auto model_tables = [&](const std::string& model, SceneSize size, const std::string& prefix) {
    ModelTables m;
    m.id = model + "-" + size_name(size);
    m.progress_prefix = prefix;
    // The paper's row sits beside ours only at the paper's size (not beside quick runs).
    m.paper_model =
        config.with_models() ? (size == file_model_size(model) ? model : "") : paper_model_of(size);
    m.scene = table_scene(model, size, steps, config.default_tolerance(), config.models_dir);
    m.warmup = warmup;
    m.cholmod_measured = config.table_cholmod_measured();
    m.check_steps = check_steps;
    m.roofs = roofs;
    m.roofs_one = roofs_one;
    m.progress = config.progress;
    return m;
  };
  // A unit: one model at one size, its rows of every table (kept for --resume).
  auto unit = [&](const std::string& model, SceneSize size, const std::string& suffix,
                  const std::function<void(json&, ModelTables&)>& rows) {
    const std::string id = model + "-" + size_name(size);
    const std::string prefix = progress.begin(id + suffix);
    const json part = report_unit(
        config, "tables", id + suffix,
        [&] {
          ModelTables m = model_tables(model, size, prefix);
          json p = json::object();
          rows(p, m);
          return p;
        },
        prefix);
    for (const auto& [table, rows_of_unit] : part.items())
      for (const json& row : rows_of_unit) tables[table].push_back(row);
    progress.finish();
  };
  for (const std::string& model : config.models()) {
    for (SceneSize size : config.table_sizes(model))
      unit(model, size, "", [&](json& part, ModelTables& m) {
        add_model_rows(part, m, model, size, config, threads);
      });
    for (SceneSize size : config.multigrid_only_sizes(model))
      unit(model, size, " (multigrid only)", [&](json& part, ModelTables& m) {
        part["multigrid"].push_back(multigrid_row(m, HierarchyKind::Meshes));
        part["multigrid"].push_back(
            multigrid_row(m, HierarchyKind::Meshes, false, kSizeIndependentCoarsening));
      });
  }
  tables["size_independence"] = size_independence(tables["multigrid"], "quadruped", 0);
  tables["size_independence_fixed_ratio"] =
      size_independence(tables["multigrid"], "quadruped", kSizeIndependentCoarsening);
  return tables;
}

ReportSectionTraits paper_tables_section() {
  return {"tables", "tables", "tables.json",
          "Tables 1 and 2 of the paper, measured (dynamic runs: energy-newton rotations,\n"
          "MG-PCG, gather update; naive update, polar + smoothing, CHOLMOD step,\n"
          "small strain, Jacobi-PCG), the paper's rows, and the oracle checks",
          [](const ReportConfig& config, std::vector<ReportRecord>&) {
            return run_paper_tables(config);
          }};
}

}  // namespace corofem
