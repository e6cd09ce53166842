#include "multigrid/hierarchy_builder.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "multigrid/lattice_level.hpp"
#include "multigrid/mesh_level.hpp"

namespace corofem {

namespace {

/// Why coarse mesh h (coarse_meshes[h - 1]) cannot be level h below a level of `above` vertices,
/// or "" when it can.
std::string mesh_level_rejection(const std::vector<TetMesh>& coarse_meshes, int h, int above,
                                 double min_coarsening) {
  if (static_cast<int>(coarse_meshes.size()) < h)
    return "no coarse mesh for level " + std::to_string(h) +
           " (a coarsened surface would keep too few vertices, or gmsh could not fill it)";
  const TetMesh& mesh = coarse_meshes[h - 1];
  if (mesh.num_vertices() * min_coarsening <= above) return "";
  return "mesh '" + mesh.source + "' has " + std::to_string(mesh.num_vertices()) +
         " vertices against " + std::to_string(above) + " on the level above (fewer than " +
         general_number(min_coarsening) + "x fewer)";
}

}  // namespace

int coarsest_vertex_limit(const HierarchyParams& params, int fine_vertices) {
  if (params.coarsest_vertices != kCoarsestSizedByFine) return params.coarsest_vertices;
  return static_cast<int>(std::ceil(std::sqrt(40.0 * std::max(fine_vertices, 0))));
}

BuiltHierarchy build_hierarchy(const TetMesh& fine, const std::vector<char>& fixed,
                               const HierarchyParams& params,
                               const std::vector<TetMesh>& coarse_meshes) {
  BuiltHierarchy built;
  std::vector<Vec3> points = fine.rest;
  std::vector<char> level_fixed = fixed;
  double cell = params.first_cell_factor * mean_edge_length(fine);
  double spacing = mean_edge_length(fine);  // of the last level built
  std::string fallback;                     // why the meshes ended, once they have
  const int limit = coarsest_vertex_limit(params, fine.num_vertices());
  for (int h = 1; h < params.levels; ++h) {
    if (h > 1 && limit > 0 && static_cast<int>(points.size()) <= limit) break;  // small enough
    CoarseLevel coarse;
    CoarseLevelOrigin origin;
    if (params.kind == HierarchyKind::Meshes && fallback.empty()) {
      fallback = mesh_level_rejection(coarse_meshes, h, static_cast<int>(points.size()),
                                      params.min_coarsening);
      if (!fallback.empty() && static_cast<int>(points.size()) <= params.end_below_vertices) {
        built.ended_early = fallback + ": level " + std::to_string(h - 1) + " is the coarsest";
        break;
      }
      if (!fallback.empty()) cell = params.first_cell_factor * spacing;
    }
    if (params.kind == HierarchyKind::Lattice || !fallback.empty()) {
      coarse = make_lattice_level(points, level_fixed, cell);
      if (coarse.transfer.coarse == 0) break;  // nothing left to coarsen
      origin.cell = cell;
      if (!fallback.empty()) {
        origin.kind = CoarseLevelOrigin::Kind::LatticeForMesh;
        origin.fallback = fallback;
      }
      spacing = cell;
      cell *= 2;
    } else {
      const TetMesh& mesh = coarse_meshes[h - 1];
      origin.kind = CoarseLevelOrigin::Kind::Mesh;
      origin.mesh = mesh.source;
      origin.mesh_vertices = mesh.num_vertices();
      origin.mesh_tets = mesh.num_tets();
      coarse = make_mesh_level(points, level_fixed, mesh, mesh.source, &origin.fit);
      spacing = mean_edge_length(mesh);
    }
    built.levels.push_back(origin);
    built.transfers.push_back(std::move(coarse.transfer));
    points = std::move(coarse.points);
    level_fixed.clear();  // coarse levels have no fixed vertices
  }
  // Lattice levels below, while the coarsest is too big to factor cheaply every step.
  const int lattice_limit = params.coarsest_max_vertices;
  while (lattice_limit > 0 && static_cast<int>(points.size()) > lattice_limit &&
         !built.transfers.empty()) {
    spacing *= 2;
    CoarseLevel coarse = make_lattice_level(points, level_fixed, spacing);
    if (2 * coarse.transfer.coarse > static_cast<int>(points.size())) break;  // not worth a level
    CoarseLevelOrigin origin;
    origin.kind = CoarseLevelOrigin::Kind::LatticeBelowCoarsest;
    origin.cell = spacing;
    built.levels.push_back(origin);
    built.transfers.push_back(std::move(coarse.transfer));
    points = std::move(coarse.points);
  }
  return built;
}

}  // namespace corofem
