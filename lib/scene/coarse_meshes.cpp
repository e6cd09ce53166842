#include "scene/coarse_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

#include "core/errors.hpp"
#include "mesh/coarse_surface_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/locality_order.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"

namespace corofem {

MeshSpec coarse_mesh_spec(const MeshSpec& fine, int h, const std::string& scene_name) {
  const int given = static_cast<int>(fine.levels.size());
  if (h <= given) return fine.levels[h - 1];
  MeshSpec spec = given > 0 ? fine.levels[given - 1] : fine;
  spec.levels.clear();
  const int doublings = h - given;
  const double factor = std::ldexp(1.0, doublings);
  switch (spec.kind) {
    case MeshSpec::Kind::File:
      throw InputError(
          "scene '" + scene_name + "': multigrid level " + std::to_string(h) +
          " needs a coarse mesh: a mesh file cannot be re-meshed, so mesh.levels must "
          "give one per level below the fine one (or use analysis.hierarchy 'lattice')");
    case MeshSpec::Kind::Surface:
      spec.simplify_surface = true;
      spec.size *= factor;
      break;
    case MeshSpec::Kind::Quadruped:
      spec.size *= factor;
      break;
    case MeshSpec::Kind::Box:
      for (int& n : spec.cells)
        n = std::max(std::min(n, 2), static_cast<int>(std::ceil(n / factor)));
      break;
  }
  return spec;
}

namespace {

/// The mesh of a derived or given level's spec; `surface` is the fine surface, read once.
TetMesh mesh_of(const MeshSpec& spec, const std::optional<SurfaceMesh>& surface) {
  return spec.simplify_surface ? tetrahedralize_coarsened_surface(*surface, spec.path, spec.size)
                               : load_scene_mesh(spec);
}

/// Whether `spec` is a surface coarsened below the fewest vertices that still follow the body.
bool too_coarse(const MeshSpec& spec, const std::optional<SurfaceMesh>& surface) {
  return spec.simplify_surface &&
         coarsened_surface_vertices(*surface, spec.size) < kMinCoarsenedSurfaceVertices;
}

/// A coarse level's mesh and the size it was meshed at (the next level starts from it).
struct SizedMesh {
  TetMesh mesh;
  double size = 0;
};

/// A derived level of about `wanted` vertices: `spec` (its size twice the level above's) meshed,
/// and re-meshed at a corrected size while its count misses by more than 15%, at most 4 times.
/// The count goes as size^-p, p between 2 (a mesh whose surface sets its vertices) and 3 (its
/// volume): the first correction takes p = 2.5, later ones the slope of the last two meshings.
/// The closest mesh is kept; nullopt where even the first size is too coarse for the surface.
std::optional<SizedMesh> mesh_near_vertex_count(MeshSpec spec, double wanted,
                                                const std::optional<SurfaceMesh>& surface) {
  constexpr int kMeshings = 4;
  const double tolerance = std::log(1.15);
  std::optional<SizedMesh> best;
  double best_miss = 0, last_log_size = 0, last_miss = 0;
  double log_size = std::log(spec.size);
  for (int k = 0; k < kMeshings; ++k) {
    spec.size = std::exp(log_size);
    if (too_coarse(spec, surface)) break;  // finer than this was meshed, or nothing is
    TetMesh mesh;
    try {
      mesh = mesh_of(spec, surface);
    } catch (const InputError&) {
      if (!best) throw;  // the first size must mesh (coarse_meshes says why not)
      break;             // keep the closest mesh made so far
    }
    const double miss = std::log(mesh.num_vertices() / wanted);  // > 0: too many vertices
    if (!best || std::abs(miss) < std::abs(best_miss)) {
      best = SizedMesh{std::move(mesh), spec.size};
      best_miss = miss;
    }
    if (std::abs(miss) <= tolerance) break;
    double p = 2.5;
    if (k > 0 && log_size != last_log_size)
      p = std::clamp(-(miss - last_miss) / (log_size - last_log_size), 1.5, 3.5);
    last_log_size = log_size;
    last_miss = miss;
    log_size += miss / p;
  }
  return best;
}

/// Whether coarse level h of `fine` can be derived where the scene gives none (a mesh file
/// cannot be re-meshed).
bool derivable(const MeshSpec& fine, int h) {
  const int given = static_cast<int>(fine.levels.size());
  return h <= given || (given > 0 ? fine.levels[given - 1] : fine).kind != MeshSpec::Kind::File;
}

}  // namespace

std::vector<TetMesh> coarse_meshes(const MeshSpec& fine, int levels, const std::string& name,
                                   int fine_vertices, double coarsening, int coarsest_limit) {
  std::vector<TetMesh> meshes;
  int above = fine_vertices;
  double size_above = fine.size;
  std::optional<SurfaceMesh> surface;  // read once for every coarsened level
  const int given = static_cast<int>(fine.levels.size());
  for (int h = 1; h < levels; ++h) {
    // A hierarchy that stops at a vertex limit takes the levels a mesh file gives, and no more.
    if (h > 1 && coarsest_limit > 0 && !derivable(fine, h)) break;
    MeshSpec spec = coarse_mesh_spec(fine, h, name);
    if (spec.simplify_surface && !surface) surface = read_surface(spec.path);
    // Derived levels sized by their vertex count, each from the size of the level above (the
    // doubling of coarse_mesh_spec is the first guess).
    const bool by_count = h > given && coarsening > 0 && above > 0 &&
                          (spec.kind == MeshSpec::Kind::Quadruped || spec.simplify_surface);
    if (by_count) spec.size = 2 * size_above;
    // A surface too coarse to follow the body ends the meshes (the hierarchy says so).
    if (too_coarse(spec, surface)) break;
    std::optional<SizedMesh> sized;
    try {
      sized = by_count ? mesh_near_vertex_count(spec, above / coarsening, surface)
                       : SizedMesh{mesh_of(spec, surface), spec.size};
    } catch (const InputError& e) {
      if (!spec.simplify_surface) throw;  // a level the scene gives must load
      std::cerr << "corofem: warning: scene '" << name << "': multigrid level " << h
                << " could not be meshed from the coarsened surface (" << e.what()
                << "); lattice levels from there on\n";
      break;
    }
    if (!sized) break;
    size_above = sized->size;
    TetMesh& mesh = sized->mesh;
    if (spec.reorder) sort_for_locality(mesh);
    mesh.source = "level " + std::to_string(h) + " (" + mesh.source + ")";
    validate_mesh(mesh);
    const int vertices = mesh.num_vertices();
    meshes.push_back(std::move(mesh));
    // The hierarchy replaces a mesh that does not coarsen, and every level below it, by lattice
    // levels (and says why): meshing those would be wasted.
    if (above > 0 && vertices * HierarchyParams{}.min_coarsening > above) break;
    if (coarsest_limit > 0 && vertices <= coarsest_limit)
      break;  // the coarsest (hierarchy_builder)
    above = vertices;
  }
  return meshes;
}

std::vector<TetMesh> coarse_meshes(const Scene& scene, int fine_vertices) {
  const AnalysisSpec& a = scene.analysis;
  if (!builds_hierarchy(a.solver) || a.multigrid.hierarchy.kind != HierarchyKind::Meshes) return {};
  return coarse_meshes(scene.mesh, a.multigrid.hierarchy.levels, scene.name, fine_vertices,
                       a.multigrid.hierarchy.coarsening,
                       coarsest_vertex_limit(multigrid_params(a).hierarchy, fine_vertices));
}

}  // namespace corofem
