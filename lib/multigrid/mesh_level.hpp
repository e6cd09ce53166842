#pragma once
// A coarser level given by a tet mesh of the same body (the paper's non-nested hierarchy): every
// free point of the finer level is interpolated in the coarse tet that contains it, or the
// nearest one (extrapolated; see point_location.hpp).
#include <string>

#include "multigrid/transfer.hpp"

namespace corofem {

/// How well a coarse mesh covers the finer level's points.
struct MeshLevelFit {
  int located = 0;                  ///< free points given weights
  int outside = 0;                  ///< of those, outside the coarse mesh (extrapolated)
  int far_outside = 0;              ///< of those, farther outside than a coarse mean edge
  double max_outside_distance = 0;  ///< largest distance of an outside point, in coarse mean edges
  double max_abs_weight = 0;        ///< largest |R_il| (1 when nothing is extrapolated)
  int dropped_vertices = 0;         ///< coarse vertices supporting no point
};

/// Transfer from `points` (the finer level) to `coarse`. Points with `fixed` set get no weights,
/// and coarse vertices supporting no point are dropped (their rows of E would be zero). Throws
/// InputError naming `name` when the mesh does not overlap the points: more than half of them
/// farther outside it than its mean edge length, or one farther than a quarter of the points'
/// bounding-box diagonal. (A coarser surface of the same body may leave most of the finer
/// level's points, its surface vertices, just outside: the bunny's L2 leaves 60% of L1's.)
CoarseLevel make_mesh_level(const std::vector<Vec3>& points, const std::vector<char>& fixed,
                            const TetMesh& coarse, const std::string& name,
                            MeshLevelFit* fit = nullptr);

}  // namespace corofem
