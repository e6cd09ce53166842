#pragma once
// "mueller2016": Mueller, Bender, Chentanez and Macklin, "A Robust Method to Extract the
// Rotational Part of Deformations" (2016). Warm-started from the previous rotation R = [r1 r2 r3],
// iterate omega = sum_i r_i x a_i / (|sum_i r_i . a_i| + 1e-9), q <- exp(omega) q, for the columns
// a_i of F, until |omega| < tolerance or the iteration cap. Always a proper rotation.
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// One element: returns the rotation and sets the iterations taken.
Mat3 mueller2016_rotation(const Mat3& a, const Mat3& warm, int max_iterations, double tolerance,
                          int& iterations);

class Mueller2016Extractor : public RotationExtractor {
 public:
  /// `params`: mueller_iterations, mueller_tolerance (mueller2016_traits declares them).
  Mueller2016Extractor(const TetMesh& mesh, const Parameters& params);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  int iterations_;
  double tolerance_;
  std::vector<Mat3> rest_edge_inverse_;
};

/// The registration of this method (rotation/rotation_method.hpp).
RotationMethodTraits mueller2016_traits();

}  // namespace corofem
