#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "linalg/linear_solver.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/component_settings.hpp"
#include "scene/json_fields.hpp"
#include "scene/memory_estimate.hpp"
#include "solver/mpi_launch.hpp"

namespace corofem {
namespace fs = std::filesystem;

namespace {

// Ranges of scene numbers (README, "Scene limits"). Within them every product a run forms
// (stiffness ~ E L, mass ~ rho L^3, M / dt^2, rho g L^3, forces over areas) stays between 1e-100
// and 1e100, far from a double's range, however absurd the combination.
constexpr double kMaxLength = 1e9;     // every coordinate, extent, size, translation, centre
constexpr double kMinLength = 1e-9;    // extents and mesh sizes
constexpr double kMinMaterial = 1e-9;  // young, density
constexpr double kMaxYoung = 1e15;     // Pa: diamond is 1.2e12
constexpr double kMaxDensity = 1e9;
constexpr double kMaxAcceleration = 1e9;  // gravity components
constexpr double kMaxForce = 1e18;        // forces[].total components
constexpr double kMinDt = 1e-9, kMaxDt = 1e6;
constexpr double kMaxDamping = 1e9;  // rayleigh alpha (1/s) and beta (s)
/// A static run's iterative rotation methods find their rotations this much tighter than the
/// run's tolerance, unless `rotation_params` says otherwise (read_analysis).
constexpr double kStaticRotationMargin = 1e-5;

std::string number_text(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

std::string range_text(double lo, double hi) {
  return "in [" + number_text(lo) + ", " + number_text(hi) + "]";
}

/// A number key with its fallback, required to lie in [lo, hi].
double number_in(JsonFields& f, const std::string& key, std::optional<double> fallback, double lo,
                 double hi) {
  const double value = f.number(key, fallback);
  if (!(value >= lo && value <= hi)) f.fail(key, range_text(lo, hi));
  return value;
}

/// [x, y, z] with every |component| <= bound.
Vec3 vec3_within(JsonFields& f, const std::string& key, std::optional<Vec3> fallback,
                 double bound) {
  const Vec3 v = f.vec3(key, fallback);
  if (!(v.cwiseAbs().maxCoeff() <= bound)) f.fail(key, "3 numbers within +-" + number_text(bound));
  return v;
}

AxisBox read_box(const nlohmann::json& value, const std::string& path, const std::string& file) {
  if (!value.is_array() || value.size() != 2)
    throw InputError("scene '" + file + "': " + path + " must be [[x0,y0,z0],[x1,y1,z1]]");
  AxisBox box{json_vec3(value[0], path + "[0]", file), json_vec3(value[1], path + "[1]", file)};
  if (!(std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff()) <= kMaxLength))
    throw InputError("scene '" + file + "': " + path + " must have coordinates within +-" +
                     number_text(kMaxLength));
  if ((box.lo.array() > box.hi.array()).any())
    throw InputError("scene '" + file + "': " + path +
                     " has a lower corner above its upper corner");
  return box;
}

template <class F>
void for_each_entry(JsonFields& parent, const std::string& key, F&& read) {
  const nlohmann::json* list = parent.get(key);
  if (!list) return;
  if (!list->is_array())
    throw InputError("scene '" + parent.file() + "': " + parent.path_of(key) + " must be an array");
  for (std::size_t i = 0; i < list->size(); ++i)
    read(
        JsonFields((*list)[i], parent.path_of(key) + "[" + std::to_string(i) + "]", parent.file()));
}

std::string one_of(JsonFields& f, const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed) {
  std::string value = f.string(key, fallback);
  for (const auto& a : allowed)
    if (a == value) return value;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  f.fail(key, "one of: " + list + " (got '" + value + "')");
}

/// A setting given by name: its value in `table` (one of its names, else the message above).
template <class Enum, std::size_t N>
Enum one_of(JsonFields& f, const std::string& key, Enum fallback, const NameTable<Enum, N>& table) {
  return *table.find(one_of(f, key, table.name(fallback), table.names()));
}

MeshSpec read_mesh(JsonFields f, const fs::path& base, bool coarse = false) {
  MeshSpec m;
  m.reorder = f.boolean("reorder", false);
  if (!coarse)
    for_each_entry(f, "levels",
                   [&](JsonFields level) { m.levels.push_back(read_mesh(level, base, true)); });
  const int sources = f.has("file") + f.has("surface") + f.has("box") + f.has("shape");
  if (sources != 1)
    f.fail("file",
           "given alone: a mesh is exactly one of file, surface+size, box+cells, shape+size");
  if (f.has("file")) {
    m.kind = MeshSpec::Kind::File;
    m.path = base / f.string("file");
  } else if (f.has("surface") || f.has("shape")) {
    if (f.has("surface")) {
      m.kind = MeshSpec::Kind::Surface;
      m.path = base / f.string("surface");
      m.simplify_surface = f.boolean("simplify", false);
    } else {
      m.kind = MeshSpec::Kind::Quadruped;
      one_of(f, "shape", "", {"quadruped"});
    }
    m.size = number_in(f, "size", std::nullopt, kMinLength, kMaxLength);
    if (m.kind == MeshSpec::Kind::Quadruped)  // gmsh gives about 2.6 / size^3 tets (11k at 0.062,
                                              // 67k at 0.033)
      m.estimated_tets = 2.6 / std::pow(m.size, 3);
  } else {
    m.kind = MeshSpec::Kind::Box;
    m.box = f.vec3("box");
    if (!(m.box.minCoeff() >= kMinLength && m.box.maxCoeff() <= kMaxLength))
      f.fail("box", "3 extents " + range_text(kMinLength, kMaxLength));
    const nlohmann::json& cells = f.require("cells");
    if (!cells.is_array() || cells.size() != 3) f.fail("cells", "an array of 3 integers");
    double tets = 6;
    for (int i = 0; i < 3; ++i) {
      if (!cells[i].is_number_integer() || cells[i].get<long long>() < 1 ||
          cells[i].get<long long>() > 100000)
        f.fail("cells", "3 integers in [1, 100000]");
      m.cells[i] = cells[i].get<int>();
      tets *= m.cells[i];
    }
    m.estimated_tets = tets;
  }
  f.reject_unknown_keys();
  return m;
}

void check_material(JsonFields& f, const std::string& key, double value) {
  if (key == "young" && !(value >= kMinMaterial && value <= kMaxYoung))
    f.fail(key, range_text(kMinMaterial, kMaxYoung));
  if (key == "poisson" && !(value > -1 && value < 0.5)) f.fail(key, "in (-1, 0.5)");
  if (key == "density" && !(value >= kMinMaterial && value <= kMaxDensity))
    f.fail(key, range_text(kMinMaterial, kMaxDensity));
}

void read_material(JsonFields f, Scene& s) {
  for (const char* key : {"young", "poisson"}) {
    const double v = f.number(key);
    check_material(f, key, v);
    (std::string(key) == "young" ? s.material.young : s.material.poisson) = v;
  }
  s.material.density = f.number("density", 0.0);
  if (f.has("density")) check_material(f, "density", s.material.density);
  for_each_entry(f, "regions", [&](JsonFields r) {
    MaterialRegion region;
    region.box = read_box(r.require("box"), r.path_of("box"), r.file());
    for (const char* key : {"young", "poisson", "density"}) {
      if (!r.has(key)) continue;
      const double v = r.number(key);
      check_material(r, key, v);
      (std::string(key) == "young"     ? region.young
       : std::string(key) == "poisson" ? region.poisson
                                       : region.density) = v;
    }
    r.reject_unknown_keys();
    s.regions.push_back(region);
  });
  f.reject_unknown_keys();
}

/// An integer key with its fallback, required to lie in [lo, hi].
int integer_in(JsonFields& f, const std::string& key, int fallback, int lo, int hi) {
  const int value = f.integer(key, fallback);
  if (value < lo || value > hi)
    f.fail(key, "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return value;
}

/// The multigrid solvers' settings. Without `levels`, the hierarchy is sized by the scene: at most
/// kSizedHierarchyMaxLevels levels, down to `coarsest_vertices` (by default a limit that follows
/// the fine mesh). The other solvers have 1 level.
void read_multigrid_settings(JsonFields& f, AnalysisSpec& a) {
  const bool sized = builds_hierarchy(a.solver) && !f.has("levels");
  a.multigrid.hierarchy.levels =
      integer_in(f, "levels", sized ? kSizedHierarchyMaxLevels : 1, 1, 16);
  a.multigrid.hierarchy.coarsest_vertices =
      f.has("coarsest_vertices") ? integer_in(f, "coarsest_vertices", 0, 1, 1'000'000)
      : sized                    ? kCoarsestSizedByFine
                                 : 0;
  a.multigrid.hierarchy.coarsest_max_vertices = integer_in(
      f, "coarsest_max_vertices", a.multigrid.hierarchy.coarsest_max_vertices, 0, 1'000'000);
  a.multigrid.hierarchy.coarsening =
      number_in(f, "coarsening", a.multigrid.hierarchy.coarsening, 0, 64);
  if (a.multigrid.hierarchy.coarsening > 0 && a.multigrid.hierarchy.coarsening < 2)
    f.fail("coarsening", "0 or in [2, 64]");
  a.multigrid.vcycles = integer_in(f, "vcycles", a.multigrid.vcycles, 0, 1000);
  a.multigrid.pre_smoothing = a.multigrid.post_smoothing =
      integer_in(f, "smoothing", a.multigrid.pre_smoothing, 1, 100);
  a.multigrid.smoother = one_of(f, "smoother", a.multigrid.smoother, smoother_names());
  // The smoother's own settings, by its declarations; another smoother's, given too (a scene that
  // sweeps smoothers), are checked by theirs and left unused.
  for (const std::string& name : smoother_names()) {
    const Parameters given = read_parameters(f, find_smoother(name)->parameters);
    if (name == a.multigrid.smoother) a.multigrid.smoother_parameters = given;
  }
  a.multigrid.cycle = one_of(f, "cycle", a.multigrid.cycle, kCycleShapes);
  a.multigrid.galerkin_refresh_change =
      number_in(f, "galerkin_refresh", a.multigrid.galerkin_refresh_change, 0, 1);
  // The stationary multigrid refactors at every update unless told otherwise: without CG around
  // it, a kept factor's stale coarse solve can make the cycle diverge (multigrid-update-notes.md).
  a.multigrid.coarsest_refactor_change = number_in(
      f, "coarsest_refactor",
      a.solver == SolverKind::Multigrid ? 0.0 : a.multigrid.coarsest_refactor_change, 0, 1);
  if (a.solver == SolverKind::PetscMg)
    // PETSc's PCMG on our transfers: its own V-cycle of Chebyshev-Jacobi smoothing (as many steps
    // as `smoothing`) and its coarse operators by MatPtAP. A setting it cannot honour is refused,
    // not ignored.
    for (const std::string& key : keys_petsc_mg_cannot_honour())
      if (f.has(key))
        f.fail(key,
               "left out with solver 'petsc-mg' (PETSc's PCMG runs its own V-cycle of "
               "Chebyshev-Jacobi smoothing, `smoothing` steps, and its own Galerkin product; it "
               "cannot honour this setting)");
}

/// The solver's own settings, by its declarations (SolverTraits::parameters). Another solver's,
/// given too (a scene that sweeps solvers), are checked by their declarations and left unused;
/// one given away from its default is said to be ignored.
void read_solver_parameters(JsonFields& f, AnalysisSpec& a) {
  std::set<std::string> own, ignored;
  for (const ParameterSpec& spec : a.solver.traits().parameters) own.insert(spec.key);
  for (const SolverKind kind : solver_kinds()) {
    const std::vector<ParameterSpec>& specs = kind.traits().parameters;
    const Parameters given = read_parameters(f, specs);
    if (kind == a.solver) {
      a.solver_parameters = given;
      continue;
    }
    for (const ParameterSpec& spec : specs)
      if (f.has(spec.key) && !own.count(spec.key) &&
          given.values().find(spec.key)->second != spec.fallback)
        ignored.insert(f.path_of(spec.key) + " (" + kind.name() + "'s)");
  }
  if (ignored.empty()) return;
  std::string list;
  for (const std::string& key : ignored) list += (list.empty() ? "" : ", ") + key;
  std::cerr << "corofem: warning: scene '" << f.file() << "': " << list
            << " belong to other solvers; ignored with solver '" << a.solver.name() << "'\n";
}

/// rotation_params: the run's method's own settings, by its declarations (after the tolerance:
/// a static run tightens the method's stopping tolerances). Every registered method's settings
/// are known keys there (a scene that sweeps methods), checked by their declarations.
void read_rotation_params(JsonFields& f, AnalysisSpec& a) {
  const RotationMethodTraits& method = a.rotation.traits();
  Parameters p(method.parameters);
  if (a.type == AnalysisType::Static) {
    // A static residual is the user's criterion: the iterative methods' rotations, found to their
    // dynamic default 1e-9, left a floor in it (3e-9 on the bunny under gravity, 8e-8 to 1e-7 on
    // the dragon, which then never reached 1e-8); found kStaticRotationMargin x tighter than the
    // tolerance they no longer set it (the bunny 3e-11 to 1e-13, as energy-exact's closed form).
    const double tight = std::max(kMinTolerance, kStaticRotationMargin * a.tolerance);
    for (const std::string& key : method.static_tolerances)
      p.set(key, std::min(p.number(key), tight));
  }
  if (const nlohmann::json* params = f.get("rotation_params")) {
    JsonFields r(*params, f.path_of("rotation_params"), f.file());
    for (const RotationMethod other : rotation_methods()) {
      const Parameters given = read_parameters(r, other.traits().parameters);
      if (other != a.rotation) continue;
      for (const ParameterSpec& spec : method.parameters)
        if (r.has(spec.key)) p.set(spec.key, given.values().find(spec.key)->second);
    }
    r.reject_unknown_keys();
  }
  a.rotation_params = std::move(p);
}

void read_analysis(JsonFields f, AnalysisSpec& a) {
  a.type = one_of(f, "type", a.type, kAnalysisTypes);
  a.formulation = one_of(f, "formulation", a.formulation, kFormulations);
  a.integrator =
      one_of(f, "integrator",
             a.type == AnalysisType::Static ? Integrator::Newton : Integrator::LinearImplicit,
             kIntegrators);
  a.rotation =
      *find_rotation_method(one_of(f, "rotation", a.rotation.name(), rotation_method_names()));
  a.solver = *find_solver(one_of(f, "solver", a.solver.name(), solver_names()));
  if (a.solver == SolverKind::Auto && a.integrator == Integrator::Newton &&
      a.formulation == Formulation::Corotational)
    // Its candidates solve a symmetric system each step; corotated Newton's tangent is not.
    f.fail("solver",
           "a named solver with integrator 'newton' and a corotational formulation ('auto' times "
           "mgpcg against jacobi-pcg on the symmetric systems of a linearly implicit run; Newton's "
           "corotated tangent is not symmetric)");
  a.multigrid.galerkin = one_of(f, "galerkin", a.multigrid.galerkin, kGalerkinMethods);
  a.multigrid.hierarchy.kind = one_of(f, "hierarchy", a.multigrid.hierarchy.kind, kHierarchyKinds);
  read_multigrid_settings(f, a);
  a.start = one_of(f, "start", a.start, kSolveStarts);
  a.start_history = integer_in(f, "start_history", a.start_history, 2, 16);
  a.dt = number_in(f, "dt", a.dt, kMinDt, kMaxDt);
  a.steps = integer_in(f, "steps", a.steps, 1, 10'000'000);
  a.load_steps = integer_in(f, "load_steps", a.load_steps, 1, 100000);
  a.tolerance = number_in(f, "tolerance", a.tolerance, kMinTolerance, 0.5);
  a.max_iterations = integer_in(f, "max_iterations", a.max_iterations, 1, 100000);
  a.max_step_cuts = integer_in(f, "max_step_cuts", a.max_step_cuts, 0, 10);
  a.factorization = one_of(f, "factorization", a.factorization, kFactorizations);
  read_solver_parameters(f, a);
  if (const nlohmann::json* damping = f.get("rayleigh")) {
    JsonFields d(*damping, f.path_of("rayleigh"), f.file());
    a.rayleigh_alpha = number_in(d, "alpha", 0.0, 0.0, kMaxDamping);
    a.rayleigh_beta = number_in(d, "beta", 0.0, 0.0, kMaxDamping);
    d.reject_unknown_keys();
  }
  read_rotation_params(f, a);
  if (!builds_hierarchy(a.solver)) {
    // A scene that sweeps solvers keeps its multigrid settings: ignored here, said once.
    std::string ignored;
    for (const std::string& key : multigrid_analysis_keys())
      if (f.has(key)) ignored += (ignored.empty() ? "" : ", ") + f.path_of(key);
    if (!ignored.empty())
      std::cerr << "corofem: warning: scene '" << f.file() << "': " << ignored
                << " belong to multigrid solvers; ignored with solver '" << a.solver.name()
                << "'\n";
    a.multigrid.hierarchy.levels = 1;
    a.multigrid.hierarchy.coarsest_vertices = 0;
  }
  f.reject_unknown_keys();
}

LoadTiming read_timing(JsonFields& f) {
  LoadTiming t;
  t.ramp_steps = integer_in(f, "ramp_steps", 0, 0, 10'000'000);
  t.release_step = integer_in(f, "release_step", 0, 0, 10'000'000);
  if (t.release_step > 0 && t.release_step <= t.ramp_steps)
    f.fail("release_step", "after ramp_steps (" + std::to_string(t.ramp_steps) + ")");
  return t;
}

}  // namespace

double LoadTiming::factor(int step) const {
  if (release_step > 0 && step >= release_step) return 0;
  return ramp_steps > 0 ? std::min(1.0, static_cast<double>(step) / ramp_steps) : 1.0;
}

std::vector<std::string> multigrid_analysis_keys() {
  std::vector<std::string> keys = {
      "levels",     "vcycles",  "smoothing",         "galerkin",
      "hierarchy",  "smoother", "coarsest_vertices", "coarsest_max_vertices",
      "coarsening", "cycle",    "coarsest_refactor", "galerkin_refresh"};
  for (const ParameterSpec& spec : smoother_parameters()) keys.push_back(spec.key);
  return keys;
}

std::vector<std::string> keys_petsc_mg_cannot_honour() {
  std::vector<std::string> keys = {"vcycles", "galerkin",          "smoother",
                                   "cycle",   "coarsest_refactor", "galerkin_refresh"};
  for (const ParameterSpec& spec : smoother_parameters()) keys.push_back(spec.key);
  return keys;
}

void drop_unused_multigrid_keys(nlohmann::json& analysis) {
  const auto solver = find_solver(analysis.value("solver", SolverKind::Cholmod.name()));
  if (solver && !builds_hierarchy(*solver))
    for (const std::string& key : multigrid_analysis_keys()) analysis.erase(key);
  if (solver == SolverKind::PetscMg)
    for (const std::string& key : keys_petsc_mg_cannot_honour()) analysis.erase(key);
}

Scene parse_scene(const nlohmann::json& json, const fs::path& base_dir, const std::string& name) {
  Scene s;
  s.name = name;
  s.raw = json;
  JsonFields top(json, "", name);
  s.mesh = read_mesh(top.object("mesh"), base_dir);
  read_material(top.object("material"), s);
  for_each_entry(top, "fixed", [&](JsonFields f) {
    s.fixed.push_back(read_box(f.require("box"), f.path_of("box"), f.file()));
    f.reject_unknown_keys();
  });
  s.gravity = vec3_within(top, "gravity", Vec3::Zero(), kMaxAcceleration);
  for_each_entry(top, "forces", [&](JsonFields f) {
    ForceSpec force;
    force.box = read_box(f.require("box"), f.path_of("box"), f.file());
    force.total = vec3_within(f, "total", std::nullopt, kMaxForce);
    force.timing = read_timing(f);
    f.reject_unknown_keys();
    s.forces.push_back(force);
  });
  for_each_entry(top, "moves", [&](JsonFields f) {
    MoveSpec move;
    move.box = read_box(f.require("box"), f.path_of("box"), f.file());
    move.translate = vec3_within(f, "translate", Vec3::Zero(), kMaxLength);
    if (const nlohmann::json* rotate = f.get("rotate")) {
      JsonFields r(*rotate, f.path_of("rotate"), f.file());
      move.axis = vec3_within(r, "axis", std::nullopt, kMaxLength);
      if (!(move.axis.norm() > 0)) r.fail("axis", "a nonzero vector");
      move.axis.normalize();
      move.center = vec3_within(r, "center", std::nullopt, kMaxLength);
      move.degrees = r.number("degrees");
      if (std::abs(move.degrees) > 36000) r.fail("degrees", "within +-36000");
      r.reject_unknown_keys();
    }
    move.timing = read_timing(f);
    f.reject_unknown_keys();
    s.moves.push_back(move);
  });
  // Coarse meshes are the default hierarchy wherever there are some: given, or re-meshable.
  const bool remeshable = !s.mesh.levels.empty() || s.mesh.kind != MeshSpec::Kind::File;
  s.analysis.multigrid.hierarchy.kind = remeshable ? HierarchyKind::Meshes : HierarchyKind::Lattice;
  if (const nlohmann::json* analysis = top.get("analysis"))
    read_analysis(JsonFields(*analysis, "analysis", name), s.analysis);
  if (s.mesh.estimated_tets > 0) {  // before anything is allocated; per rank under mpirun
    const AnalysisSpec& a = s.analysis;
    const int ranks =
        distributes_mesh(a.type, a.integrator, a.solver, launcher_size()) ? launcher_size() : 1;
    const NewtonTangent tangent = newton_tangent(a.type, a.integrator, a.formulation, a.solver);
    require_memory(
        s.mesh.estimated_tets, run_bytes(a.solver, s.mesh.estimated_tets, ranks, tangent),
        "scene '" + name + "': mesh." + (s.mesh.kind == MeshSpec::Kind::Box ? "cells" : "size"),
        run_bytes_basis(a.solver, ranks, tangent));
  }
  if (builds_hierarchy(s.analysis.solver) &&
      s.analysis.multigrid.hierarchy.kind == HierarchyKind::Meshes && !remeshable)
    throw InputError("scene '" + name +
                     "': analysis.hierarchy 'meshes' needs mesh.levels for a "
                     "mesh read from a file (it cannot be re-meshed); or use 'lattice'");
  if (const nlohmann::json* output = top.get("output")) {
    JsonFields o(*output, "output", name);
    s.output.rotations = o.boolean("rotations", false);
    if (o.has("vtu")) s.output.vtu = base_dir / o.string("vtu");
    o.reject_unknown_keys();
  }
  top.reject_unknown_keys();
  if (!s.moves.empty() && s.analysis.type != AnalysisType::Dynamic)
    throw InputError("scene '" + name + "': moves need a dynamic analysis");
  const bool needs_mass = s.analysis.type == AnalysisType::Dynamic || s.gravity.norm() > 0;
  if (needs_mass && !(s.material.density > 0))
    throw InputError("scene '" + name + "': material.density is required for " +
                     (s.analysis.type == AnalysisType::Dynamic ? "a dynamic analysis" : "gravity"));
  return s;
}

Scene load_scene(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError("scene file '" + file.string() + "' does not exist or is not a file");
  std::ifstream in(file);
  if (!in) throw InputError("scene file '" + file.string() + "' cannot be read");
  nlohmann::json json;
  std::string last_key;  // the key whose value the parser was reading when it failed
  const nlohmann::json::parser_callback_t track = [&](int, nlohmann::json::parse_event_t event,
                                                      nlohmann::json& parsed) {
    if (event == nlohmann::json::parse_event_t::key) last_key = parsed.get<std::string>();
    return true;
  };
  try {
    json = nlohmann::json::parse(in, track);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError("scene '" + file.string() + "' is not valid JSON: " + e.what());
  } catch (const nlohmann::json::out_of_range& e) {  // a number beyond a double's range
    throw InputError("scene '" + file.string() + "': the value of key '" + last_key +
                     "' is outside the range of a double (" + e.what() + ")");
  }
  return parse_scene(json, file.parent_path(), file.string());
}

}  // namespace corofem
