#pragma once
// How far a displacement increment stretches the mesh: what bounds a static Newton step.
#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"

namespace corofem {

/// The largest change of a tet edge under the increment `du` (3 per vertex), relative to the
/// edge's rest length: max over edges (i, j) of |du_j - du_i| / |X_j - X_i|.
double largest_edge_stretch(const TetMesh& mesh, const Eigen::VectorXd& du);

}  // namespace corofem
