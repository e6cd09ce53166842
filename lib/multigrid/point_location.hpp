#pragma once
// Point location in a tet mesh for the transfer between non-nested levels (paper section 4;
// Georgii and Westermann 2005): the barycentric coordinates of a point in the tet that contains
// it or, for a point outside the mesh, in the nearest tet. Outside, the coordinates are
// extrapolated (some negative, still summing to 1), so interpolation reproduces every affine
// field, and with it every rigid motion, exactly.
#include <array>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct TetLocation {
  int tet = -1;
  std::array<double, 4> weights{};  ///< barycentric coordinates of the point in `tet`
  double distance = 0;              ///< 0 inside; else the distance to the nearest tet
};

/// A uniform grid of buckets over the mesh's bounding box, each holding the tets whose bounding
/// boxes overlap it; built once, then every query visits a few buckets.
class TetLocator {
 public:
  TetLocator(const std::vector<Vec3>& vertices, const std::vector<Tet>& tets);

  /// Inside (within a relative 1e-12 of a face): the containing tet with the largest smallest
  /// coordinate, negative round-off clamped to 0 and the rest renormalized. Outside: the nearest
  /// tet by Euclidean distance, coordinates unclamped.
  TetLocation locate(const Vec3& p) const;

 private:
  std::array<double, 4> barycentric(int tet, const Vec3& p) const;
  double distance_to_tet(int tet, const Vec3& p) const;
  int bucket_of(const std::array<int, 3>& cell) const;
  std::array<int, 3> cell_of(const Vec3& p) const;  ///< clamped to the grid

  const std::vector<Vec3>& vertices_;
  const std::vector<Tet>& tets_;
  std::vector<Eigen::Matrix3d> inverse_edges_;  ///< per tet: [b-a, c-a, d-a]^{-1}
  Vec3 origin_;
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> bucket_start_, bucket_tets_;
};

}  // namespace corofem
