#include "tune/tune_axes.hpp"

#include <cmath>

#include "core/number_text.hpp"
#include "scene/analysis_settings.hpp"
#include "scene/time_step_scaling.hpp"

namespace corofem {
using nlohmann::json;

namespace {

/// Resolutions step by this factor in element size (3.4x the tets): far enough apart for a
/// Richardson estimate whose difference is not round-off, close enough to keep several.
constexpr double kResolutionRatio = 1.5;
constexpr int kCoarserResolutions = 3;

std::string cells_label(const std::array<int, 3>& c) {
  return "cells=" + std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]);
}

/// The resolution axis: a finer reference where affordable, the scene's mesh, coarser ones.
TuneAxis resolution_axis(const Scene& scene, const json& raw, const TuneAxesOptions& options,
                         std::string& note) {
  TuneAxis axis{.name = "resolution"};
  const MeshSpec& m = scene.mesh;
  const double given_tets = m.estimated_tets;
  auto add = [&](AxisValue v) { axis.values.push_back(std::move(v)); };
  switch (m.kind) {
    case MeshSpec::Kind::File:
      add({.label = "the scene's mesh file", .family = "resolution"});
      note = "a mesh file cannot be re-meshed: the resolution is the scene's";
      return axis;
    case MeshSpec::Kind::Box: {
      // Factors in element size: 1/1.5 (finer), 1, 1.5, 2.25, ...
      std::array<int, 3> previous{};
      for (int k = -1; k <= kCoarserResolutions; ++k) {
        const double h = std::pow(kResolutionRatio, k);
        std::array<int, 3> cells{};
        double tets = 6;
        for (int i = 0; i < 3; ++i) {
          cells[i] = std::max(1, static_cast<int>(std::lround(m.cells[i] / h)));
          tets *= cells[i];
        }
        if (k < 0 && (!options.resolution_free || tets > options.finest_tets)) continue;
        if (k > 0 && (!options.resolution_free || cells == previous)) break;
        previous = cells;
        if (k == 0) axis.given = static_cast<int>(axis.values.size());
        add({.label = cells_label(cells) + (k < 0    ? " (finer)"
                                            : k == 0 ? " (the scene's)"
                                                     : ""),
             .patch = {{"mesh", {{"cells", cells}}}},
             .family = "resolution"});
      }
      break;
    }
    case MeshSpec::Kind::Quadruped:
    case MeshSpec::Kind::Surface: {
      const bool surface = m.kind == MeshSpec::Kind::Surface;
      // gmsh keeps a surface's triangles: a finer size refines only the inside (the body stays
      // the one the surface describes); coarser sizes simplify the surface first
      // (mesh.simplify), which changes the body too.
      for (int k = -1; k <= kCoarserResolutions; ++k) {
        const double size = m.size * std::pow(kResolutionRatio, k);
        const double tets = given_tets * std::pow(m.size / size, 3);  // 0 where unknown
        if (k < 0 && (!options.resolution_free || tets > options.finest_tets)) continue;
        if (k > 0 && !options.resolution_free) break;
        if (k == 0) axis.given = static_cast<int>(axis.values.size());
        json mesh = {{"size", size}};
        // Given coarse levels finer than 1.5x the new size would not coarsen: the hierarchy
        // derives its own.
        if (k > 0 && raw["mesh"].contains("levels")) mesh["levels"] = nullptr;
        if (k > 0 && surface) mesh["simplify"] = true;
        add({.label = "size=" + general_number(size) +
                      (k < 0    ? (surface ? " (finer inside)" : " (finer)")
                       : k == 0 ? " (the scene's)"
                                : ""),
             .patch = {{"mesh", mesh}},
             .family = "resolution"});
      }
      if (surface)
        note =
            "a surface keeps its triangles: the finer reference is refined inside only, and the "
            "coarser resolutions simplify the surface (their errors include the body's change)";
      break;
    }
  }
  if (!options.resolution_free) note = "--resolution fixed: the scene's mesh only";
  axis.reference = 0;
  return axis;
}

/// Every rotation method; with `stopped_earlier`, the iterative ones also stopped earlier (their
/// own families, from the default tolerance down). Not under static Newton: its tangent assumes
/// converged rotations, and with mueller2016 at one iteration the quadruped's Newton cut its load
/// increments 256-fold and ran 6 minutes without converging.
TuneAxis rotation_axis(bool stopped_earlier) {
  TuneAxis axis{.name = "rotation"};
  const std::string& exact = RotationMethod::EnergyExact.name();
  axis.values.push_back(
      {.label = exact, .patch = {{"analysis", {{"rotation", exact}}}}, .family = exact});
  for (RotationMethod method : rotation_methods())
    if (method.traits().compared && method != RotationMethod::EnergyExact)
      axis.values.push_back({.label = method.name(),
                             .patch = {{"analysis", {{"rotation", method.name()}}}},
                             .family = method.name()});
  if (!stopped_earlier) return axis;
  for (RotationMethod method : rotation_methods()) {
    if (!method.traits().compared) continue;
    for (const LooserSetting& setting : method.traits().looser)
      for (double value : setting.values) {
        // An integral value stays an integer: the scene reads iteration counts as integers.
        const json number = value == std::trunc(value) && std::abs(value) < 1e9
                                ? json(static_cast<long long>(value))
                                : json(value);
        axis.values.push_back(
            {.label = method.name() + " " + setting.param + "=" + general_number(value),
             .patch = {{"analysis",
                        {{"rotation", method.name()},
                         {"rotation_params", {{setting.param, number}}}}}},
             .family = method.name()});
      }
  }
  return axis;
}

std::string tolerance_label(double tolerance) {
  return "tol=" + general_number(tolerance);
}

/// A linear solver's settings: CHOLMOD, then families of iterative solvers, each from its
/// tightest tolerance to its loosest.
TuneAxis linear_solver_axis(const Scene& scene) {
  TuneAxis axis{.name = "solver"};
  axis.values.push_back(
      {.label = "cholmod", .patch = {{"analysis", {{"solver", "cholmod"}}}}, .family = "cholmod"});
  // No patch names `levels`: merged onto the scene, each keeps the scene's own hierarchy size
  // (its `levels` and `coarsest_vertices`, or the size the scene gives where it names neither).
  auto family = [&](const std::string& name, json settings, const std::vector<double>& tolerances) {
    for (double tolerance : tolerances) {
      json a = settings;
      a["tolerance"] = tolerance;
      axis.values.push_back({.label = name + " " + tolerance_label(tolerance),
                             .patch = {{"analysis", a}},
                             .family = name});
    }
  };
  family("mgpcg", {{"solver", "mgpcg"}}, {1e-8, 1e-6, 1e-4, 1e-3, 1e-2});
  family("mgpcg W-cycle", {{"solver", "mgpcg"}, {"cycle", "W"}}, {1e-4, 1e-3, 1e-2});
  family("mgpcg chebyshev", {{"solver", "mgpcg"}, {"smoother", "chebyshev"}}, {1e-4, 1e-3, 1e-2});
  family("mgpcg lattice", {{"solver", "mgpcg"}, {"hierarchy", "lattice"}}, {1e-4, 1e-3, 1e-2});
  for (int vcycles : {2, 1})
    axis.values.push_back({.label = "multigrid vcycles=" + std::to_string(vcycles),
                           .patch = {{"analysis", {{"solver", "multigrid"}, {"vcycles", vcycles}}}},
                           .family = "multigrid"});
  family("jacobi-pcg", {{"solver", "jacobi-pcg"}}, {1e-6, 1e-4, 1e-3, 1e-2});
  // Where a solve's start counts (a corotated linearly implicit step): the iterative solvers
  // started from the projection on the last velocities, which pays where iterations are many
  // (lib/README, "The solve's start").
  const AnalysisSpec& a = scene.analysis;
  if (a.type == AnalysisType::Dynamic && a.integrator == Integrator::LinearImplicit &&
      a.formulation == Formulation::Corotational) {
    family("mgpcg projected start", {{"solver", "mgpcg"}, {"start", "projection"}},
           {1e-4, 1e-3, 1e-2});
    family("jacobi-pcg projected start", {{"solver", "jacobi-pcg"}, {"start", "projection"}},
           {1e-4, 1e-3, 1e-2});
  }
  return axis;
}

/// Static Newton (whichever way the scene solves its tangent): its convergence tolerance, from the
/// reference's 1e-8 (a relative residual whose displacement error is far below any target; tighter
/// ones can sit on the rounding floor: the quadruped at 1e-10 with the exact minimizer stalled at
/// 3e-10) down. Where the scene factors its tangent, the same tolerances with the tangent by GMRES
/// on corofem's multigrid (`mgpcg`: integrate/preconditioned_gmres_solve.hpp), which from some
/// 10k tets takes a fraction of the factorizations' time and memory (lib/README.md).
TuneAxis newton_tolerance_axis(const Scene& scene) {
  TuneAxis axis{.name = "solver"};
  const auto family = [&](const std::string& name, const json& settings) {
    for (double t : {1e-8, 1e-6, 1e-4, 1e-3, 1e-2}) {
      json a = settings;
      a["tolerance"] = t;
      axis.values.push_back(
          {.label = name + " " + tolerance_label(t), .patch = {{"analysis", a}}, .family = name});
    }
  };
  family("newton", json::object());
  const AnalysisSpec& a = scene.analysis;
  if (newton_tangent(a.type, a.integrator, a.formulation, a.solver) == NewtonTangent::Factored)
    family("newton mgpcg", {{"solver", "mgpcg"}});
  return axis;
}

/// Static corotational: load increments, the scene's first, then halved down to one.
TuneAxis load_steps_axis(const Scene& scene) {
  TuneAxis axis{.name = "load_steps"};
  for (int n = scene.analysis.load_steps;; n = std::max(1, n / 2)) {
    axis.values.push_back({.label = "load_steps=" + std::to_string(n),
                           .patch = {{"analysis", {{"load_steps", n}}}},
                           .family = "load_steps"});
    if (n == 1) break;
  }
  return axis;
}

/// Dynamic: the time step, the scene's first, then 2x, 4x and 8x where the step counts allow.
TuneAxis time_step_axis(const Scene& scene, const json& raw) {
  TuneAxis axis{.name = "time_step"};
  for (int k : {1, 2, 4, 8}) {
    if (k > 1 && !time_step_scaled(raw, k, 1)) break;
    axis.values.push_back({.label = "dt=" + general_number(scene.analysis.dt * k),
                           .time_factor = k,
                           .family = "time_step"});
  }
  return axis;
}

}  // namespace

std::vector<TuneAxis> tune_axes(const Scene& scene, const json& raw, const TuneAxesOptions& options,
                                std::string& note) {
  std::vector<TuneAxis> axes;
  axes.push_back(resolution_axis(scene, raw, options, note));
  const bool corotational = scene.analysis.formulation == Formulation::Corotational;
  const bool dynamic = scene.analysis.type == AnalysisType::Dynamic;
  const bool static_newton = !dynamic && scene.analysis.integrator == Integrator::Newton;
  if (corotational) axes.push_back(rotation_axis(!static_newton));
  if (static_newton && corotational) {
    axes.push_back(newton_tolerance_axis(scene));
    axes.push_back(load_steps_axis(scene));
  } else {
    axes.push_back(linear_solver_axis(scene));
  }
  if (dynamic) axes.push_back(time_step_axis(scene, raw));
  // The scene's own value where it is one of an axis's values.
  for (TuneAxis& axis : axes) {
    if (axis.name == "resolution") continue;
    for (std::size_t i = 0; i < axis.values.size(); ++i) {
      json patched = raw;
      patched.merge_patch(axis.values[i].patch);
      if (patched == raw && axis.values[i].time_factor == 1) axis.given = static_cast<int>(i);
    }
  }
  return axes;
}

int time_factor(const std::vector<TuneAxis>& axes, const std::vector<int>& setting) {
  int factor = 1;
  for (std::size_t i = 0; i < axes.size(); ++i) factor *= axes[i].values[setting[i]].time_factor;
  return factor;
}

std::optional<json> apply_setting(const json& raw, const std::vector<TuneAxis>& axes,
                                  const std::vector<int>& setting) {
  json scene = raw;
  for (std::size_t i = 0; i < axes.size(); ++i) scene.merge_patch(axes[i].values[setting[i]].patch);
  scene.erase("output");
  drop_unused_multigrid_keys(scene["analysis"]);
  const int factor = time_factor(axes, setting);
  return factor == 1 ? std::optional<json>(scene) : time_step_scaled(scene, factor, 1);
}

}  // namespace corofem
