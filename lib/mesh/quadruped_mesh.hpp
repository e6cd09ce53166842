#pragma once
// A procedural quadruped (a stand-in for the paper's horse when no models folder is given): a box
// body, four cylindrical legs, a cylindrical neck and a box head, fused with gmsh's OpenCASCADE
// kernel and filled with tets. Meters, standing on z = 0, facing +x:
//   body  x in [0, 1.6], y in [-0.25, 0.25], z in [1.0, 1.5]
//   legs  radius 0.08 from z = 0 to z = 1.05 at x = 0.15 (hind) and 1.45 (fore), y = +-0.15;
//         knees are the band z in [0.45, 0.6], hooves z < 0.05
//   neck  radius 0.13 from (1.45, 0, 1.35) to (1.9, 0, 1.95);  head x in [1.8, 2.25],
//         y in [-0.1, 0.1], z in [1.85, 2.08]
#include "mesh/tet_mesh.hpp"

namespace corofem {

/// The quadruped meshed with gmsh's Mesh.MeshSizeMax = `size` (m). About 11k tets at 0.062,
/// 34k at 0.042 and 67k at 0.033 (see bench/scenes). Each size is meshed once per process and
/// kept. Throws InputError for size <= 0.
TetMesh make_quadruped_mesh(double size);

}  // namespace corofem
