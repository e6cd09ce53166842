#include "cli/commands.hpp"

#include <iostream>
#include <map>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "scene/export_matrices.hpp"
#include "scene/run_scene.hpp"

namespace corofem {
namespace {

const char* kToolHelp = R"(corofem: corotated finite elements with Galerkin multigrid (Georgii and Westermann 2008)

Usage: corofem <command> [options]

Commands:
  run SCENE.json --out RESULT.json   static or dynamic run of one scene
  export-matrices SCENE.json --out DIR
                                     Matrix Market files of every level's system matrix
                                     and transfer operator, and levels.json
  help [COMMAND]                     this text, or a command's

Exit status: 0 success, 1 did not converge or numerical fault, 2 bad input.
)";

const char* kRunHelp = R"(Usage: corofem run SCENE.json --out RESULT.json

Runs one scene (see README, "Scene format") and writes RESULT.json: node_tags, rest,
displacement (input node order), converged, iterations, residual, timings_ms, the scene and the
context (commit, compiler, flags, machine); with output.rotations also element_tags and rotations
(unit quaternions [w,x,y,z] of the final state). Progress goes to stderr.
Exit status: 0 converged, 1 did not converge or NaN/inf, 2 bad input (nothing is written).
)";

const char* kExportHelp = R"(Usage: corofem export-matrices SCENE.json --out DIR

Runs the scene's first linear solve through the multigrid hierarchy of analysis.levels (1 for
cholmod scenes) and writes, for each level h, A<h>.mtx (3n_h x 3n_h) and R<h>.mtx (3n_{h+1} x 3n_h,
level h to h+1) in Matrix Market coordinate real general, DOF index 3*vertex+component, and
levels.json with the sizes. A<h+1> is exactly R<h> A<h> R<h>^T as the solver computed it.
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

int run_command(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(args, {"--out"}, {});
  if (parsed.help) {
    std::cout << kRunHelp;
    return 0;
  }
  if (parsed.positional.size() != 1) throw InputError("run needs exactly one SCENE.json (see --help)");
  if (!parsed.options.count("--out")) throw InputError("run needs --out RESULT.json");
  const std::filesystem::path out = parsed.options["--out"];
  check_writable(out);
  Scene scene = load_scene(parsed.positional[0]);
  if (scene.output.vtu) check_writable(*scene.output.vtu);
  SceneRun run = run_scene(scene, &std::cerr);
  write_file_atomically(out, [&](std::ostream& o) { o << run.record.dump(1) << '\n'; });
  if (!run.converged) {
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
  if (command == "export-matrices") return export_command(rest);
  throw InputError("unknown command '" + command + "' (see corofem --help)");
}

}  // namespace corofem
