#pragma once
// "polar-smoothed" (paper section 5): polar decomposition of F, then passes of 1-ring quaternion
// averaging weighted by element volume: q_e <- sum_n V_n s_n q_n / |sum_n V_n s_n q_n| over the
// elements n sharing a vertex with e, s_n = sign(q_e . q_n) so that q and -q (the same rotation)
// do not cancel. A reflection from polar (inverted element) enters as the quaternion of -Q.
#include <Eigen/Geometry>

#include "mesh/element_adjacency.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

class SmoothedPolarExtractor : public RotationExtractor {
 public:
  /// `params`: smoothing_passes (polar_smoothed_traits declares it).
  SmoothedPolarExtractor(const TetMesh& mesh, const Parameters& params);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  int passes_;
  std::vector<Mat3> rest_edge_inverse_;
  std::vector<double> volume_;
  ElementRings rings_;
};

/// The registration of this method (rotation/rotation_method.hpp).
RotationMethodTraits polar_smoothed_traits();

}  // namespace corofem
