#include "cli/commands.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>

#include "cli/export_matrices.hpp"
#include "cli/run_scene.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/threads.hpp"
#include "report/report_driver.hpp"
#include "solver/mpi_launch.hpp"

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
  help [COMMAND]                     this text, or a command's

Exit status: 0 success, 1 did not converge or numerical fault, 2 bad input.
)";

const char* kRunHelp = R"(Usage: corofem run SCENE.json --out RESULT.json [--threads N]

Runs one scene (see README, "Scene format") and writes RESULT.json: node_tags, rest,
displacement (input node order), converged, iterations, residual, timings_ms, the scene and the
context (commit, compiler, flags, machine); with output.rotations also element_tags and rotations
(unit quaternions [w,x,y,z] of the final state). Progress goes to stderr.
  --threads N    threads of the step's kernels (default: all cores, or OMP_NUM_THREADS; "all";
                 under mpirun, the cores shared among the machine's ranks); the result is
                 bit-identical at every count
Under `mpirun -np N` with analysis.solver petsc-gamg, hypre-boomeramg or petsc-mg, the linear
solves are distributed over the N ranks (each owns a contiguous share of the vertices); every
rank builds and assembles the whole system (replicated), and rank 0 alone writes RESULT.json,
the VTU and the progress. RESULT.json's "mpi" says how many ranks ran.
Exit status: 0 converged, 1 did not converge or NaN/inf, 2 bad input (nothing is written).
)";

const char* kExportHelp = R"(Usage: corofem export-matrices SCENE.json --out DIR

Runs the scene's first linear solve through the multigrid hierarchy of analysis.levels (1 for
cholmod scenes) and writes, for each level h, A<h>.mtx (3n_h x 3n_h) and R<h>.mtx (3n_{h+1} x 3n_h,
level h to h+1) in Matrix Market coordinate real general, DOF index 3*vertex+component, and
levels.json with the sizes. A<h+1> is exactly R<h> A<h> R<h>^T as the solver computed it.
)";

const char* kReportHelp =
    R"(Usage: corofem report [--out DIR] [--full | --quick | --smoke] [--models DIR] [--only NAME]
                      [--tables-only | --speed-accuracy-only | --stability-only | --model-accuracy-only]
                      [--vtu] [--no-render] [--threads N]

Runs the report's sections and writes into DIR (default out/report):
  tables.json          Tables 1 and 2 of the paper, measured (dynamic runs: energy-newton rotations,
                       MG-PCG, gather update; naive update, polar + smoothing, CHOLMOD step,
                       small strain, Jacobi-PCG), the paper's rows, and the oracle checks
  speed_accuracy.json  time per step against error for solver settings, rotation methods and
                       resolutions, with the Pareto front and the cheapest setting meeting targets
  stability.json       every rotation extractor on scenes built to break them, under linearly
                       implicit and Newton Euler at two steps: stable, flutter or diverged, with
                       flutter, inversion, energy and asymmetry measurements and the cause of each
                       failure (method or integrator)
  model_accuracy.json  every rotation extractor's static solve against CalculiX NLGEOM on the same
                       meshes and loads, and the linear solve against CalculiX's (needs ccx)
then draws REPORT.md and charts/*.png from the JSON alone (reports/render; needs matplotlib).
A cache_profile.json (bench/cache_profile.sh) and an mpi_scaling.json (bench/mpi_scaling.py) in DIR,
both run by ci/report, are included.

  (default)      Table 1 at the paper's three sizes, small versions of every other section
                 (about 7 minutes on 2 cores; longer with --models)
  --full         every table and sweep at the paper's sizes, the stability study at full length
                 (about an hour)
  --quick        small versions of every section (about 5 minutes)
  --smoke        a seconds-long run for the report's own tests
  --models DIR   the bunny, horse and dragon surfaces instead of the procedural scenes
  --only NAME    just one model (cantilever, twisting-bar, quadruped, bunny, horse, dragon) or
                 stability scene (bar-twist, bar-stretch, block-squash, quadruped-stretched,
                 quadruped-posed, horse-stretched, horse-stretched-paper, horse-posed)
  --vtu          VTU frames of the stability runs (every 10th step) under DIR/vtu/
  --no-render    JSON only
  --threads N    threads of the step's kernels (default: all cores; "all"); Table 1 is measured
                 at one thread and at N
Progress goes to stderr. A failing case is recorded ("completed": false) and the report goes on.
Exit status: 0 written, 2 bad options.
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
  if (!distributed || (scene.analysis.integrator == Integrator::Newton &&
                       scene.analysis.formulation == Formulation::Corotational))
    throw InputError(
        scene.name + ": analysis.solver '" + kSolverKinds.name(solver) + "'" +
        (distributed ? " with integrator 'newton' (a serial sparse LU)" : "") +
        " under mpirun -np " + std::to_string(ranks) +
        ": only petsc-gamg, hypre-boomeramg and petsc-mg distribute their solves over ranks");
}

/// --threads N (or "all"): the count every parallel kernel uses from here on.
void apply_threads_option(const ParsedArgs& parsed) {
  if (parsed.options.count("--threads"))
    set_thread_count(parse_thread_count(parsed.options.at("--threads")));
}

int run_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(args, {"--out", "--threads"}, {});
  if (parsed.help) {
    std::cout << kRunHelp;
    return 0;
  }
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
  if (!writer) scene.output.vtu.reset();
  if (scene.output.vtu) check_writable(*scene.output.vtu);
  SceneRun run = run_scene(scene, writer ? &std::cerr : nullptr);
  run.record["mpi"] = {
      {"ranks", mpi.size},
      {"distributed", mpi.size > 1 ? "the linear solves (PETSc); assembly replicated on every rank"
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
  ParsedArgs parsed =
      parse_args(args, {"--out", "--models", "--only", "--threads"},
                 {"--full", "--quick", "--smoke", "--tables-only", "--speed-accuracy-only",
                  "--stability-only", "--model-accuracy-only", "--vtu", "--no-render"});
  if (parsed.help) {
    std::cout << kReportHelp;
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
  const int only =
      parsed.options.count("--tables-only") + parsed.options.count("--speed-accuracy-only") +
      parsed.options.count("--stability-only") + parsed.options.count("--model-accuracy-only");
  if (only > 1)
    throw InputError(
        "report: give at most one of --tables-only, --speed-accuracy-only, --stability-only, "
        "--model-accuracy-only");
  if (only == 1) {
    config.tables = parsed.options.count("--tables-only") > 0;
    config.speed_accuracy = parsed.options.count("--speed-accuracy-only") > 0;
    config.stability = parsed.options.count("--stability-only") > 0;
    config.model_accuracy = parsed.options.count("--model-accuracy-only") > 0;
  }
  config.vtu = parsed.options.count("--vtu") > 0;
  if (parsed.options.count("--only")) config.only = parsed.options["--only"];
  apply_threads_option(parsed);
  std::error_code ec;
  std::filesystem::create_directories(config.out_dir, ec);
  if (ec)
    throw InputError("report: cannot create the output folder '" + config.out_dir.string() +
                     "': " + ec.message());
  check_writable(config.out_dir / "tables.json");
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

}  // namespace

int dispatch(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h" ||
      (args[0] == "help" && args.size() == 1)) {
    std::cout << kToolHelp;
    return args.empty() ? 2 : 0;
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
  throw InputError("unknown command '" + command + "' (see corofem --help)");
}

}  // namespace corofem
