#pragma once
// Generated box meshes: the embedded scenes' meshes need no external data.
#include <array>

#include "mesh/tet_mesh.hpp"

namespace corofem {

/// Box [0,Lx]x[0,Ly]x[0,Lz] of nx*ny*nz cells, each split into 6 tets around its main diagonal
/// (Kuhn split, the same in every cell, so faces match and the mesh is conforming).
/// Vertex (i,j,k) has index i + (nx+1)*(j + (ny+1)*k); tags are index + 1.
TetMesh make_box_mesh(const Vec3& size, const std::array<int, 3>& cells);

}  // namespace corofem
