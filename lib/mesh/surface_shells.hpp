#pragma once
// The closed shells a surface file holds and how they nest: one STL can describe several bodies
// side by side, and a hollow body as its outer shell with its voids' shells inside.
#include <vector>

#include "mesh/surface_mesh.hpp"

namespace corofem {

struct SurfaceShell {
  SurfaceMesh surface;  ///< this shell's triangles and the vertices they use
  int inside = -1;      ///< the shell that immediately encloses this one; -1: none
  int depth = 0;        ///< how many shells enclose it: even, a body's outer shell; odd, a void's
};

/// The surface's shells (triangles joined through shared vertices; vertices at the same
/// coordinates count as one), in order of their first triangle, with their nesting: a shell lies
/// inside another when a vertex of it does (rays cast three ways, crossings counted, the
/// majority's parity). Shells are taken not to cross each other; gmsh refuses ones that do.
std::vector<SurfaceShell> surface_shells(const SurfaceMesh& surface);

/// The volume the shells' bodies fill: each body's enclosed volume less its voids', whichever way
/// the triangles face (a shell's triangles are first turned to agree with their neighbours).
double filled_volume(const std::vector<SurfaceShell>& shells);

}  // namespace corofem
