#include "cli/commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "cli/export_matrices.hpp"
#include "cli/run_scene.hpp"
#include "compare/comparison_output.hpp"
#include "core/atomic_file.hpp"
#include "core/build_info.hpp"
#include "core/errors.hpp"
#include "core/folder_lock.hpp"
#include "core/number_text.hpp"
#include "core/threads.hpp"
#include "report/report_driver.hpp"
#include "report/report_section.hpp"
#include "report/scene_catalogue.hpp"
#include "scene/scene_paths.hpp"
#include "scene/scene_simulation.hpp"
#include "solver/mpi_launch.hpp"
#include "tune/scene_tuner.hpp"

namespace corofem {
namespace {

const char* kToolHelp =
    R"(corofem: corotated finite elements with Galerkin multigrid (Georgii and Westermann 2008)

Usage: corofem <command> [options]

Commands:
  run SCENE.json --out RESULT.json   static or dynamic run of one scene
  export-matrices SCENE.json --out DIR
                                     Matrix Market files of every level's system matrix
                                     and transfer operator, and levels.json
  report [--out DIR] [--full | --quick] [--models DIR] [--tables-only | --stability-only]
                                     the main job: paper tables, speed against accuracy,
                                     stability study (JSON), REPORT.md and charts
  tune SCENE.json --target E [--out DIR]
                                     the cheapest settings of a scene that meet an error
                                     target, checked in a re-run
  compare BASE NEW [--out DIR]       whether NEW is faster, slower or the same as BASE (run
                                     records, report folders, Google Benchmark JSON), with
                                     intervals; exit 1 on a regression
  help [COMMAND]                     this text, or a command's
  --version                          the version, commit, compiler and flags of this binary

Exit status: 0 success, 1 did not converge or numerical fault, 2 bad input.
)";

const char* kRunHelp = R"(Usage: corofem run SCENE.json --out RESULT.json [--threads N]
                   [--count-phases perf|callgrind[:FILE]]

Runs one scene (see README, "Scene format") and writes RESULT.json: node_tags, rest,
displacement (input node order), converged, iterations, residual, timings_ms, the scene and the
context (commit, compiler, flags, machine); with output.rotations also element_tags and rotations
(unit quaternions [w,x,y,z] of the final state). Progress goes to stderr.
  --threads N    threads of the step's kernels (default: all cores, or OMP_NUM_THREADS; "all";
                 under mpirun, the cores shared among the machine's ranks); the result is
                 bit-identical at every count
  --count-phases SOURCE
                 also count each phase's and solver part's instructions, D1 and last-level
                 misses from the first step on, into RESULT.json's phase_counts: "perf" from the
                 hardware's counters (where the machine has none, the record says why and holds
                 timings only), "callgrind" from valgrind's simulated caches, exact and the same
                 on every host: run under valgrind --tool=callgrind --instr-atstart=no
                 --combine-dumps=yes --cache-sim=yes (bench/count_phases.py does; FILE: the
                 --callgrind-out-file given to valgrind). Counts are one thread's at --threads 1
Under `mpirun -np N` with analysis.solver petsc-gamg, hypre-boomeramg or petsc-mg, the linear
solves are distributed over the N ranks (each owns a contiguous share of the vertices). A dynamic
linearly implicit or a static scene (lagged or Newton: the corotated tangent by PETSc's GMRES)
runs on a distributed mesh (PT-Scotch's partition): each rank keeps only its part (the tets
touching its vertices and their halo), rotates and assembles that, and solves its rows; rank 0
writes RESULT.json with the fields gathered and "ranks" (per rank: owned and held tets, owned
and halo vertices, peak RSS, phase times; max and min), and output.vtu becomes a parallel VTU
(.pvtu, one piece per rank). Dynamic Newton runs (a serial sparse factorization) are refused
under mpirun.
RESULT.json's "mpi" says how many ranks ran and what was distributed.
Exit status: 0 converged, 1 did not converge or NaN/inf, 2 bad input (nothing is written).
)";

const char* kExportHelp = R"(Usage: corofem export-matrices SCENE.json --out DIR

Runs the scene's first linear solve through the multigrid hierarchy of analysis.levels (1 for
cholmod scenes) and writes, for each level h, A<h>.mtx (3n_h x 3n_h) and R<h>.mtx (3n_{h+1} x 3n_h,
level h to h+1) in Matrix Market coordinate real general, DOF index 3*vertex+component, and
levels.json with the sizes. A<h+1> is exactly R<h> A<h> R<h>^T as the solver computed it.
)";

/// `names` joined by ", ".
std::string comma_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

/// `text` broken at spaces into lines of at most `width` characters, the first `first_used`
/// characters of the first already taken, the others indented by `indent` spaces.
std::string wrapped(const std::string& text, std::size_t width, std::size_t first_used,
                    std::size_t indent) {
  std::string out;
  std::size_t used = first_used;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (used + 1 + word.size() > width && used > indent) {
      out += "\n" + std::string(indent, ' ');
      used = indent;
    } else if (!out.empty()) {
      out += ' ';
      ++used;
    }
    out += word;
    used += word.size();
  }
  return out;
}

/// `corofem report --help`: the sections' flags and records come from their registry, the names
/// --only takes from the scene catalogue.
std::string report_help() {
  std::string flags, records;
  for (const std::string& name : report_section_names()) {
    const ReportSectionTraits& section = report_section(name);
    flags += (flags.empty() ? "" : " | ") + ("--" + name + "-only");
    std::string file = "  " + section.file;
    file.resize(std::max<std::size_t>(file.size() + 1, 23), ' ');
    std::string usage = section.usage;
    for (std::size_t at = usage.find('\n'); at != std::string::npos; at = usage.find('\n', at + 1))
      usage.insert(at + 1, std::string(23, ' '));
    records += file + usage + "\n";
  }
  std::vector<std::string> models = procedural_models(), files = file_models();
  models.insert(models.end(), files.begin(), files.end());
  const std::string only_names =
      wrapped("just one model (" + comma_list(models) + ") or stability scene (" +
                  comma_list(stability_scene_ids(true)) + ")",
              100, 17, 17);
  return R"(Usage: corofem report [--out DIR] [--full | --quick | --smoke] [--models DIR] [--only NAME]
                      [)" +
         flags + R"(]
                      [--vtu] [--no-render] [--threads N] [--resume]

Runs the report's sections and writes into DIR (default out/report):
)" + records +
         R"(then draws REPORT.md and charts/*.png from the JSON alone (reports/render; needs matplotlib).
A cache_profile.json (bench/cache_profile.sh) and an mpi_scaling.json (bench/mpi_scaling.py) in DIR,
both run by ci/report, are included.

  (default)      Table 1 at the paper's three sizes, small versions of every other section
                 (about 5 minutes on 2 cores; longer with --models)
  --full         every table and sweep at the paper's sizes, the stability study at full length
                 (about an hour)
  --quick        small versions of every section (about 5 minutes)
  --smoke        a seconds-long run for the report's own tests
  --models DIR   the bunny, horse and dragon surfaces instead of the procedural scenes
  --only NAME    )" +
         only_names + R"(
  --NAME-only    just that section
  --vtu          VTU frames of the stability runs (every 10th step) under DIR/vtu/
  --no-render    JSON only
  --threads N    threads of the step's kernels (default: all cores; "all"); Table 1 is measured
                 at one thread and at N
  --resume       go on with a report into DIR that was killed (at any moment, SIGKILL too), with
                 the options it began with: every section and unit it finished is kept (a table
                 model at a size, a sweep's scene, a stability scene and method, a model-accuracy
                 case), the rest runs; the records are an uninterrupted run's but for times
Progress goes to stderr. A failing case is recorded ("completed": false) and the report goes on.
Exit status: 0 written, 2 bad options.
)";
}

const char* kTuneHelp =
    R"(Usage: corofem tune SCENE.json --target E [--quantity displacement|tip|probe]
                    [--probe X0,Y0,Z0,X1,Y1,Z1] [--resolution free|fixed] [--budget MINUTES]
                    [--out DIR] [--threads N] [--no-render]

Finds the cheapest settings of the scene (ms per step) whose answer stays within the relative
error E of the reference, and writes into DIR (default out/tune):
  tuned_scene.json  the answer: the scene with the tuned settings, for `corofem run`
  tune.json         the reference and its own error, every setting measured (error, ms per step,
                    Pareto front), the answer and its re-run, what produced it
  pareto.png        cost against error of every setting measured (reports/render; matplotlib)
The reference: the finest resolution (a box or the quadruped re-meshed 1.5x finer where it stays
under 300k tets; a surface refined inside), CHOLMOD (static Newton: its sparse LU at 1e-8),
the exact rotation minimizer, the scene's time step and integrator. Its own discretization error
is estimated by Richardson extrapolation from coarser resolutions and counted in every error.
The search: resolution, rotation method, solver and tolerance (multigrid hierarchy, smoother and
cycle, Jacobi-PCG, dynamic: the projected start; static Newton: its tolerance, with the tangent
factored or on mgpcg), static
load increments, the time step (dynamic; unstable steps are recorded and left out), each screened
alone, then their combinations, cheapest predicted first.
  --target E       relative error in (0, 1) of the quantity
  --quantity Q     displacement: the whole final field (default); tip: the final displacement of
                   the vertex farthest from the supports; probe: the mean final displacement of
                   the vertices in the --probe box
  --resolution R   free (default): coarser meshes are candidates and the reference's own
                   discretization error counts; fixed: the scene's mesh only, errors against
                   the exact solve on it
  --budget M       minutes for the search (default 5); the reference, the scene as given and the
                   answer's re-run always run
Progress goes to stderr.
Exit status: 0 the target is met in the re-run; 1 not met (the closest setting and why:
discretization-limited, where the reference's own error is above the target; the reference not
converging; the budget); 2 bad input.
)";

const char* kCompareHelp =
    R"(Usage: corofem compare BASE NEW [--threshold T] [--alpha A] [--accuracy-factor F]
                       [--field-tolerance E] [--min-ms M] [--count-threshold C]
                       [--miss-threshold D] [--min-count N] [--suspect-factor S]
                       [--paired-only] [--out DIR]

BASE and NEW are each a `corofem run` record, a report folder (tables.json, speed_accuracy.json,
cache_profile.json), Google Benchmark JSON from corofem_bench, or a folder of such records: records
of the same case (ci/bench-gate's repetitions) are runs of one row. Rows pair by what was run
(case and its scene's content, thread count, phase or field); a case run on different scenes is
refused. Warns where machine, compiler or flags differ.
  timed rows     (phase times, per step or per repetition) the ratio NEW/BASE as the
                 Hodges-Lehmann estimate on log times with its distribution-free interval at
                 1 - A, and the two-sided Mann-Whitney U test; with >= 3 runs a side one
                 median per run is a sample, else the steps pooled. slower or faster needs
                 p < A and a ratio beyond 1 +- T; rows whose BASE median is under M ms are
                 shown, not gated
  counters       (CG iterations, V-cycles, roofline bytes and flops, level sizes, cachegrind
                 counts) compared exactly; all are costs, an increase is a regression
  accuracy       (errors against the oracles, static residuals) worse when grown more than F
                 times and past 1e-12
  displacements  the two runs' final fields, |u_new - u_base| / |u_base| above E is a regression
  work counts    (a counted run's phase_counts: each phase's instructions, D1 and LL misses;
                 run --count-phases, bench/count_phases.py) more or fewer when moved by more
                 than C (instructions) or D (misses), relative; more is a regression, fewer says
                 the baseline is stale; rows whose BASE is under N are shown, not gated; counts
                 made by another tool, compiler, flags or simulated caches are not compared. A
                 timed row whose phase was also counted on both sides says whether its counts
                 moved (the code's) or not (the machine's)
  --threshold T  default 0.05       --alpha A            default 0.01
  --accuracy-factor F  default 2    --field-tolerance E  default 1e-8
  --paired-only  compare only the cases both sides ran on the same scenes (a report against a
                 snapshot of other scenes); the rest is summarized in a line each, no regression
  --suspect-factor S  default 2: a row too short of runs to test whose ratio is beyond S either
                 way is suspect (slower: a regression), not passed; the headline is inconclusive
                 where rows went untested, with the runs a side that would test them
  --min-ms M     default 0.05       --count-threshold C  default 0.005
  --miss-threshold D  default 0.05  --min-count N        default 20000
  --out DIR      also writes DIR/compare.md, compare.json (the verdict) and compare.svg (the
                 ratios with their intervals)
The Markdown table goes to stdout.
Exit status: 0 nothing regressed, 1 a regression, 2 bad input (unreadable or unpairable records,
named with the file and row).
)";

/// Options of the form --key value, plus positional arguments.
struct ParsedArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;
  bool help = false;
};

ParsedArgs parse_args(const std::vector<std::string>& args, const std::vector<std::string>& valued,
                      const std::vector<std::string>& flags) {
  ParsedArgs parsed;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      parsed.help = true;
    } else if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      if (i + 1 >= args.size()) throw InputError("option " + a + " needs a value");
      parsed.options[a] = args[++i];
    } else if (std::find(flags.begin(), flags.end(), a) != flags.end()) {
      parsed.options[a] = "1";
    } else if (a.rfind("--", 0) == 0) {
      throw InputError("unknown option '" + a + "' (see --help)");
    } else {
      parsed.positional.push_back(a);
    }
  }
  return parsed;
}

/// Under mpirun only the PETSc and hypre solvers are distributed: any other would run the same
/// serial solve on every rank.
void require_distributed_solver(const Scene& scene, int ranks) {
  const SolverKind solver = scene.analysis.solver;
  const bool distributed = is_petsc_solver(solver);
  const AnalysisSpec& a = scene.analysis;
  if (!distributed)
    throw InputError(
        scene.name + ": analysis.solver '" + solver.name() + "' under mpirun -np " +
        std::to_string(ranks) +
        ": only petsc-gamg, hypre-boomeramg and petsc-mg distribute their solves over ranks");
  if (a.type == AnalysisType::Dynamic && a.integrator == Integrator::Newton &&
      a.formulation == Formulation::Corotational)
    throw InputError(
        scene.name + ": a dynamic scene with analysis.integrator 'newton' (a serial " +
        "sparse factorization) under mpirun -np " + std::to_string(ranks) +
        ": use 'linear-implicit', the paper's linearly implicit Euler, which runs on " +
        "a distributed mesh");
}

/// --threads N (or "all"): the count every parallel kernel uses from here on.
void apply_threads_option(const ParsedArgs& parsed) {
  if (parsed.options.count("--threads"))
    set_thread_count(parse_thread_count(parsed.options.at("--threads")));
}

/// --count-phases perf | callgrind[:FILE]
std::optional<PhaseCounting> parse_phase_counting(const ParsedArgs& parsed) {
  if (!parsed.options.count("--count-phases")) return std::nullopt;
  const std::string value = parsed.options.at("--count-phases");
  const std::size_t colon = value.find(':');
  const std::optional<CountSource> source = kCountSources.find(value.substr(0, colon));
  if (!source || (colon != std::string::npos && *source != CountSource::Callgrind) ||
      (colon != std::string::npos && colon + 1 == value.size()))
    throw InputError("--count-phases: '" + value +
                     "' is neither perf nor callgrind[:FILE] (see run --help)");
  PhaseCounting counting{*source, {}};
  if (colon != std::string::npos) counting.callgrind_file = value.substr(colon + 1);
  return counting;
}

int run_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(args, {"--out", "--threads", "--count-phases"}, {});
  if (parsed.help) {
    std::cout << kRunHelp;
    return 0;
  }
  const std::optional<PhaseCounting> counting = parse_phase_counting(parsed);
  const MpiLaunch mpi = mpi_launch();
  apply_threads_option(parsed);
  if (mpi.size > 1 && !parsed.options.count("--threads") && !std::getenv("OMP_NUM_THREADS"))
    set_thread_count(
        std::max(1, available_cores() / mpi.ranks_on_this_machine));  // the ranks share the cores
  if (parsed.positional.size() != 1)
    throw InputError("run needs exactly one SCENE.json (see --help)");
  if (!parsed.options.count("--out")) throw InputError("run needs --out RESULT.json");
  const std::filesystem::path out = parsed.options["--out"];
  const bool writer = mpi.rank == 0;
  if (writer) check_writable(out);
  Scene scene = load_scene(parsed.positional[0]);
  if (mpi.size > 1) require_distributed_solver(scene, mpi.size);
  const bool distributed_mesh = SceneSimulation::distributes_mesh(scene, mpi.size);
  if (!writer && !distributed_mesh) scene.output.vtu.reset();  // distributed: a piece per rank
  if (scene.output.vtu) check_writable(*scene.output.vtu);
  SceneRun run = run_scene(scene, writer ? &std::cerr : nullptr, counting);
  run.record["mpi"] = {
      {"ranks", mpi.size},
      {"distributed",
       distributed_mesh ? "the mesh, the element work (rotations, assembly, forces) and the linear "
                          "solves: each rank holds its part (rank 0 builds the whole body and "
                          "sends the parts)"
       : mpi.size > 1   ? "the linear solves (PETSc); mesh and assembly replicated on every rank"
                        : "nothing (one rank)"}};
  if (writer) write_file_atomically(out, [&](std::ostream& o) { o << run.record.dump(1) << '\n'; });
  if (!run.converged && writer) {
    std::cerr << "corofem: did not converge: " << run.record.value("message", "") << "\n";
    return 1;
  }
  return 0;
}

int export_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(args, {"--out"}, {});
  if (parsed.help) {
    std::cout << kExportHelp;
    return 0;
  }
  if (parsed.positional.size() != 1)
    throw InputError("export-matrices needs exactly one SCENE.json (see --help)");
  if (!parsed.options.count("--out")) throw InputError("export-matrices needs --out DIR");
  export_matrices(load_scene(parsed.positional[0]), parsed.options["--out"]);
  std::cerr << "corofem: matrices written to " << parsed.options["--out"] << "\n";
  return 0;
}

int report_command(const std::vector<std::string>& args) {
  std::vector<std::string> switches = {"--full", "--quick",     "--smoke",
                                       "--vtu",  "--no-render", "--resume"};
  for (const std::string& name : report_section_names()) switches.push_back("--" + name + "-only");
  ParsedArgs parsed = parse_args(args, {"--out", "--models", "--only", "--threads"}, switches);
  if (parsed.help) {
    std::cout << report_help();
    return 0;
  }
  if (!parsed.positional.empty())
    throw InputError("report takes no positional arguments (got '" + parsed.positional[0] + "')");
  ReportConfig config;
  config.progress = &std::cerr;
  if (parsed.options.count("--out")) config.out_dir = parsed.options["--out"];
  if (parsed.options.count("--full") + parsed.options.count("--quick") +
          parsed.options.count("--smoke") >
      1)
    throw InputError("report: give at most one of --full, --quick and --smoke");
  if (parsed.options.count("--full")) config.mode = ReportConfig::Mode::Full;
  if (parsed.options.count("--quick")) config.mode = ReportConfig::Mode::Quick;
  if (parsed.options.count("--smoke")) config.mode = ReportConfig::Mode::Smoke;
  if (parsed.options.count("--models")) {
    config.models_dir = parsed.options["--models"];
    std::error_code ec;
    for (const char* file : {"bunny_L0.stl", "horse_L0.stl", "dragon_L0.stl"})
      if (!std::filesystem::is_regular_file(config.models_dir / file, ec))
        throw InputError("--models " + config.models_dir.string() + ": no " + file + " there");
  }
  for (const std::string& name : report_section_names())
    if (parsed.options.count("--" + name + "-only")) config.sections.push_back(name);
  if (config.sections.size() > 1)
    throw InputError("report: give at most one --NAME-only (got --" + config.sections[0] +
                     "-only and --" + config.sections[1] + "-only)");
  config.vtu = parsed.options.count("--vtu") > 0;
  config.resume = parsed.options.count("--resume") > 0;
  if (parsed.options.count("--only")) config.only = parsed.options["--only"];
  apply_threads_option(parsed);
  prepare_output_folder(config.out_dir, "tables.json");
  const FolderLock one_writer(config.out_dir, "corofem report");
  std::cerr << "report: " << config.mode_name() << " run into " << config.out_dir.string() << "\n";
  run_report(config);
  if (!parsed.options.count("--no-render")) {
    const int rendered = render_report(config.out_dir, &std::cerr);
    if (rendered != 0)
      std::cerr << "report: the renderer exited with " << rendered
                << "; the JSON records are complete (re-draw with reports/render "
                << config.out_dir.string() << ")\n";
  }
  return 0;
}

/// The whole of `text` as a finite number, else nothing.
std::optional<double> number_from(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

double number_option(const ParsedArgs& parsed, const std::string& key, double fallback) {
  if (!parsed.options.count(key)) return fallback;
  const std::string& text = parsed.options.at(key);
  const std::optional<double> value = number_from(text);
  if (!value) throw InputError(key + " needs a number, got '" + text + "'");
  return *value;
}

/// --probe X0,Y0,Z0,X1,Y1,Z1: the box's low and high corners.
AxisBox probe_option(const std::string& text) {
  std::vector<double> v;
  std::stringstream in(text);
  bool numbers = true;
  for (std::string item; std::getline(in, item, ',');) {
    const std::optional<double> value = number_from(item);
    numbers &= value.has_value();
    if (value) v.push_back(*value);
  }
  if (!numbers || v.size() != 6 || v[0] > v[3] || v[1] > v[4] || v[2] > v[5])
    throw InputError(
        "--probe needs 6 numbers X0,Y0,Z0,X1,Y1,Z1 with X0<=X1, Y0<=Y1, Z0<=Z1, got '" + text +
        "'");
  return {Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
}

int tune_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(
      args, {"--target", "--quantity", "--probe", "--resolution", "--budget", "--out", "--threads"},
      {"--no-render"});
  if (parsed.help) {
    std::cout << kTuneHelp;
    return 0;
  }
  if (parsed.positional.size() != 1)
    throw InputError("tune needs exactly one SCENE.json (see --help)");
  if (!parsed.options.count("--target")) throw InputError("tune needs --target E (see --help)");
  TuneOptions options;
  options.progress = &std::cerr;
  options.target = number_option(parsed, "--target", 0);
  options.budget_minutes = number_option(parsed, "--budget", options.budget_minutes);
  const std::string quantity =
      parsed.options.count("--quantity") ? parsed.options["--quantity"] : "displacement";
  const auto kind = kTuneQuantities.find(quantity);
  if (!kind)
    throw InputError("--quantity must be displacement, tip or probe, got '" + quantity + "'");
  options.quantity.kind = *kind;
  if ((*kind == TuneQuantity::Probe) != (parsed.options.count("--probe") > 0))
    throw InputError("--probe BOX goes with --quantity probe, and only with it");
  if (parsed.options.count("--probe"))
    options.quantity.probe = probe_option(parsed.options["--probe"]);
  const std::string resolution =
      parsed.options.count("--resolution") ? parsed.options["--resolution"] : "free";
  if (resolution != "free" && resolution != "fixed")
    throw InputError("--resolution must be free or fixed, got '" + resolution + "'");
  options.axes.resolution_free = resolution == "free";
  apply_threads_option(parsed);
  const std::filesystem::path out_dir =
      parsed.options.count("--out") ? parsed.options["--out"] : "out/tune";
  const std::filesystem::path scene_file = parsed.positional[0];
  const Scene scene = load_scene(scene_file);  // every key checked before the long work
  prepare_output_folder(out_dir, "tune.json");
  const std::filesystem::path scene_dir =
      scene_file.parent_path().empty() ? "." : scene_file.parent_path();
  TuneOutcome outcome = tune_scene(scene.raw, scene_dir, scene_file.string(), options);
  const nlohmann::json tuned = with_paths_moved(outcome.tuned_scene, scene_dir, out_dir);
  write_file_atomically(out_dir / "tuned_scene.json",
                        [&](std::ostream& o) { o << tuned.dump(2) << '\n'; });
  outcome.record["answer"]["scene_file"] = "tuned_scene.json";
  write_file_atomically(out_dir / "tune.json",
                        [&](std::ostream& o) { o << outcome.record.dump(1) << '\n'; });
  if (!parsed.options.count("--no-render") && render_report(out_dir, nullptr, Rendering::Tune) != 0)
    std::cerr << "tune: no chart drawn (reports/render --tune " << out_dir.string() << ")\n";
  const nlohmann::json& a = outcome.record["answer"];
  std::cerr << "tune: " << a["status"].get<std::string>() << ": " << a["changes"].get<std::string>()
            << "; " << a["reason"].get<std::string>() << "\n";
  if (a.contains("rerun") && a["rerun"].value("completed", false))
    std::cerr << "tune: re-run error "
              << general_number(a["rerun"]["error_with_reference"].get<double>()) << " (target "
              << general_number(options.target) << "), "
              << general_number(a["rerun"]["cost_ms"].get<double>()) << " ms per step"
              << (a.contains("speedup_over_given")
                      ? ", " + general_number(a["speedup_over_given"].get<double>()) +
                            "x the scene as given"
                      : std::string())
              << "; written to " << (out_dir / "tuned_scene.json").string() << "\n";
  return outcome.exit_status;
}

int compare_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(
      args,
      {"--threshold", "--alpha", "--accuracy-factor", "--field-tolerance", "--min-ms", "--out",
       "--count-threshold", "--miss-threshold", "--min-count", "--suspect-factor"},
      {"--paired-only"});
  if (parsed.help) {
    std::cout << kCompareHelp;
    return 0;
  }
  if (parsed.positional.size() != 2) throw InputError("compare needs BASE and NEW (see --help)");
  CompareOptions options;
  options.threshold = number_option(parsed, "--threshold", options.threshold);
  options.alpha = number_option(parsed, "--alpha", options.alpha);
  options.accuracy_factor = number_option(parsed, "--accuracy-factor", options.accuracy_factor);
  options.field_tolerance = number_option(parsed, "--field-tolerance", options.field_tolerance);
  options.min_ms = number_option(parsed, "--min-ms", options.min_ms);
  options.count_threshold = number_option(parsed, "--count-threshold", options.count_threshold);
  options.miss_threshold = number_option(parsed, "--miss-threshold", options.miss_threshold);
  options.min_count = number_option(parsed, "--min-count", options.min_count);
  options.suspect_factor = number_option(parsed, "--suspect-factor", options.suspect_factor);
  options.paired_only = parsed.options.count("--paired-only") > 0;
  if (!(options.threshold >= 0) || !(options.alpha > 0 && options.alpha < 1) ||
      !(options.accuracy_factor >= 1) || !(options.field_tolerance >= 0) ||
      !(options.min_ms >= 0) || !(options.count_threshold >= 0) || !(options.miss_threshold >= 0) ||
      !(options.min_count >= 0) || !(options.suspect_factor >= 1))
    throw InputError(
        "compare: --threshold, --field-tolerance, --min-ms, --count-threshold, --miss-threshold "
        "and --min-count need >= 0, --alpha a number in (0, 1), --accuracy-factor and "
        "--suspect-factor >= 1");
  const std::string& base = parsed.positional[0];
  const std::string& contender = parsed.positional[1];
  if (parsed.options.count("--out")) prepare_output_folder(parsed.options["--out"], "compare.json");
  const Comparison c = compare_records(read_records(base), read_records(contender), options);
  const std::string markdown = comparison_markdown(c, base, contender);
  std::cout << markdown;
  if (parsed.options.count("--out")) {
    const std::filesystem::path out = parsed.options["--out"];
    write_file_atomically(out / "compare.md", [&](std::ostream& o) { o << markdown; });
    write_file_atomically(out / "compare.json", [&](std::ostream& o) {
      o << comparison_json(c, base, contender).dump(1) << '\n';
    });
    write_file_atomically(out / "compare.svg", [&](std::ostream& o) { o << comparison_svg(c); });
  }
  for (const std::string& w : c.warnings) std::cerr << "compare: warning: " << w << "\n";
  std::cerr << "compare: " << (c.regressed() ? "regression" : c.headline()) << "\n";
  if (c.counts_fell())
    std::cerr << "compare: work counts fell beyond their threshold: BASE's counts are stale\n";
  return c.regressed() ? 1 : 0;
}

}  // namespace

int dispatch(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h" ||
      (args[0] == "help" && args.size() == 1)) {
    std::cout << kToolHelp;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version" || args[0] == "version") {
    std::cout << "corofem " << build_version() << " (commit " << build_commit() << ", "
              << build_compiler() << ", " << build_type() << " " << build_flags() << ")\n";
    return 0;
  }
  const std::string& command = args[0] == "help" ? args[1] : args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args[0] == "help") rest = {"--help"};
  if (command == "run") return run_command(rest);
  if (mpi_launch().size > 1 && command != "help" && rest != std::vector<std::string>{"--help"})
    throw InputError(
        "corofem " + command +
        " runs on one process; under mpirun only `corofem run` (see corofem help run)");
  if (command == "export-matrices") return export_command(rest);
  if (command == "report") return report_command(rest);
  if (command == "tune") return tune_command(rest);
  if (command == "compare") return compare_command(rest);
  throw InputError("unknown command '" + command + "' (see corofem --help)");
}

}  // namespace corofem
