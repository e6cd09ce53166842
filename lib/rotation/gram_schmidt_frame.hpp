#pragma once
// "qr": the geometric frame of Nesme, Payan and Faure (2005), a QR (Gram-Schmidt) factorization
// of element edges: e1 = edge 0->1, e2 = edge 0->2 orthogonalized against e1, e3 = e1 x e2;
// Q = G_deformed G_rest^T. Exact for rigid motions and always a proper rotation, but it depends
// on the vertex order: edge 0->1 keeps its direction exactly while the other edges absorb the
// shear, so relabelling the vertices changes Q under deformation (an anisotropy).
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// Orthonormal frame [e1 e2 e3] of the tet's edges 0->1 and 0->2.
Mat3 edge_frame(const Vec3& x0, const Vec3& x1, const Vec3& x2);

class GramSchmidtFrameExtractor : public RotationExtractor {
 public:
  explicit GramSchmidtFrameExtractor(const TetMesh& mesh);
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override;

 private:
  const TetMesh& mesh_;
  std::vector<Mat3> rest_frame_;
};

/// The registration of this method (rotation/rotation_method.hpp).
RotationMethodTraits qr_traits();

}  // namespace corofem
