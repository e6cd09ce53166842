#pragma once
// Coarser surfaces of a body for the multigrid's coarse meshes: gmsh fills a closed
// surface with tets but keeps its triangles, so a bare STL re-meshed at twice the size is as fine
// at the boundary as before. Edge collapses with Garland and Heckbert's quadric error metric (1997)
// give the surface the coarser spacing first.
#include "mesh/surface_mesh.hpp"

namespace corofem {

/// What simplify_surface did.
struct SimplificationStats {
  int collapses = 0;
  int rejected = 0;  ///< collapses refused by the checks below
};

/// Collapses the edges of least cost (quadric error plus length^4: even spacing) until
/// `target_vertices` remain or no edge can collapse.
/// The surface stays a closed 2-manifold with the same orientation: an edge collapses only where
/// its end points share exactly its two opposite vertices (the link condition) and no opposite
/// vertex would drop below three neighbours; no triangle around it turns by more than 60 degrees
/// or becomes a sliver (a vertex moved across its neighbours would fold the surface over itself).
SurfaceMesh simplify_surface(const SurfaceMesh& surface, int target_vertices,
                             SimplificationStats* stats = nullptr);

/// Per vertex of `coarse`, the move outward along its normal (area-weighted) that puts the
/// vertices of `fine` nearest to it on or below its tangent plane: moved so, the coarse surface
/// covers the body, and a coarse mesh of it locates the fine points instead of extrapolating to
/// them (a surface's fine vertices are the body's outermost points).
std::vector<Vec3> covering_moves(const SurfaceMesh& coarse, const SurfaceMesh& fine);

}  // namespace corofem
