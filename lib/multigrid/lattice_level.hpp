#pragma once
// Coarse levels from covering lattices of Kuhn-split cubes: the comparison hierarchy
// (`analysis.hierarchy: "lattice"`), needing no coarse mesh.
#include "multigrid/transfer.hpp"

namespace corofem {

/// Covering lattice of Kuhn-split cubes of edge `cell`: only cells containing a point of `points`
/// are kept, so every point lies in a lattice tet; its weights are the barycentric coordinates
/// there (a closed form: with local coordinates sorted t1 >= t2 >= t3, the weights of the path
/// 000, e_a, e_a + e_b, 111 are 1 - t1, t1 - t2, t2 - t3, t3). Points with `fixed` set get no
/// weights (their DOFs take no part in the transfer); coarse vertices supporting no point are
/// dropped.
CoarseLevel make_lattice_level(const std::vector<Vec3>& points, const std::vector<char>& fixed,
                               double cell);

}  // namespace corofem
