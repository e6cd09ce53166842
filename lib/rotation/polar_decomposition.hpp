#pragma once
// Polar decomposition F = R S by Higham's scaled Newton iteration (Hauth and Strasser 2004, as in
// VegaFEM and SOFA). For det F < 0 the orthogonal factor is a reflection (det R = -1); that is
// kept on purpose: it is the behaviour of the prior work the stability study measures.
#include "element/element_rest.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// Orthogonal factor of F; `fallback` is returned when F is singular (no polar factor exists;
/// *iterations = -1 then). Converges quadratically; stops at |X_{k+1} - X_k|_F <= 1e-15 |X_k|_F
/// or 30 iterations.
Mat3 polar_rotation(const Mat3& f, const Mat3& fallback, int* iterations = nullptr);

class PolarExtractor : public RotationExtractor {
 public:
  explicit PolarExtractor(const TetMesh& mesh);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  std::vector<Mat3> rest_edge_inverse_;
};

/// Small strain: Q = I for every element.
class IdentityExtractor : public RotationExtractor {
 public:
  IdentityExtractor() : RotationExtractor(RotationMethod::None) {}
  void extract(const std::vector<Vec3>&, std::vector<Mat3>& rotations) override;
};

/// The registration of these methods (rotation/rotation_method.hpp).
RotationMethodTraits polar_traits();
RotationMethodTraits identity_traits();

}  // namespace corofem
