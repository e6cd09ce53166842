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

std::vector<TetMesh> coarse_meshes(const MeshSpec& fine, int levels, const std::string& name,
                                   int fine_vertices) {
  std::vector<TetMesh> meshes;
  int above = fine_vertices;
  std::optional<SurfaceMesh> surface;  // read once for every coarsened level
  for (int h = 1; h < levels; ++h) {
    const MeshSpec spec = coarse_mesh_spec(fine, h, name);
    if (spec.simplify_surface && !surface) surface = read_surface(spec.path);
    // A surface too coarse to follow the body ends the meshes (the hierarchy says so).
    if (spec.simplify_surface &&
        coarsened_surface_vertices(*surface, spec.size) < kMinCoarsenedSurfaceVertices)
      break;
    TetMesh mesh;
    try {
      mesh = spec.simplify_surface
                 ? tetrahedralize_coarsened_surface(*surface, spec.path, spec.size)
                 : load_scene_mesh(spec);
    } catch (const InputError& e) {
      if (!spec.simplify_surface) throw;  // a level the scene gives must load
      std::cerr << "corofem: warning: scene '" << name << "': multigrid level " << h
                << " could not be meshed from the coarsened surface (" << e.what()
                << "); lattice levels from there on\n";
      break;
    }
    if (spec.reorder) sort_for_locality(mesh);
    mesh.source = "level " + std::to_string(h) + " (" + mesh.source + ")";
    validate_mesh(mesh);
    const int vertices = mesh.num_vertices();
    meshes.push_back(std::move(mesh));
    // The hierarchy replaces a mesh that does not coarsen, and every level below it, by lattice
    // levels (and says why): meshing those would be wasted.
    if (above > 0 && vertices * HierarchyParams{}.min_coarsening > above) break;
    above = vertices;
  }
  return meshes;
}

std::vector<TetMesh> coarse_meshes(const Scene& scene, int fine_vertices) {
  const AnalysisSpec& a = scene.analysis;
  if (!is_multigrid_solver(a.solver) || a.hierarchy != HierarchyKind::Meshes) return {};
  return coarse_meshes(scene.mesh, a.levels, scene.name, fine_vertices);
}

}  // namespace corofem
