#pragma once
// Vertex and element order for cache locality: vertices along a Morton (Z-order) curve of their
// rest positions, tets by their smallest vertex. Meshers number vertices in no useful order; on
// gmsh meshes this makes assembly, SpMV and Gauss-Seidel 2-3x slower than on a lattice's order.
#include "mesh/tet_mesh.hpp"

namespace corofem {

/// Reorders the mesh in place; node and element tags travel with their vertices and tets.
void sort_for_locality(TetMesh& mesh);

}  // namespace corofem
