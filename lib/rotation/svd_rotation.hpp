#pragma once
// "polar-fixed": SVD with inversion handling (Irving, Teran and Fedkiw 2004). F = U S V^T with U
// and V proper rotations and the smallest singular value negated when det F < 0; R = U V^T. Always
// a proper rotation, continuous through det F = 0 (except where two singular values tie).
#include "rotation/rotation_extractor.hpp"

namespace corofem {

class InversionAwareSvdExtractor : public RotationExtractor {
 public:
  explicit InversionAwareSvdExtractor(const TetMesh& mesh);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  std::vector<Mat3> rest_edge_inverse_;
};

/// Dm^{-1} of every element (shared by the extractors that need F).
std::vector<Mat3> rest_edge_inverses(const TetMesh& mesh);

/// The registration of this method (rotation/rotation_method.hpp).
RotationMethodTraits polar_fixed_traits();

}  // namespace corofem
