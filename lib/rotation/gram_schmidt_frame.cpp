#include "rotation/gram_schmidt_frame.hpp"

#include "core/threads.hpp"

namespace corofem {

Mat3 edge_frame(const Vec3& x0, const Vec3& x1, const Vec3& x2) {
  const Vec3 e1 = (x1 - x0).normalized();
  const Vec3 d2 = x2 - x0;
  const Vec3 e2 = (d2 - d2.dot(e1) * e1).normalized();
  Mat3 g;
  g << e1, e2, e1.cross(e2);
  return g;
}

GramSchmidtFrameExtractor::GramSchmidtFrameExtractor(const TetMesh& mesh)
    : RotationExtractor(RotationMethod::Qr), mesh_(mesh) {
  rest_frame_.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets)
    rest_frame_.push_back(edge_frame(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]]));
}

void GramSchmidtFrameExtractor::extract(const std::vector<Vec3>& positions,
                                        std::vector<Mat3>& rotations) {
  stats_.iterations.assign(mesh_.tets.size(), 0);
  int fallbacks = 0;
#pragma omp parallel for schedule(static) reduction(+ : fallbacks) num_threads(threads_for(mesh_.num_tets()))
  for (int e = 0; e < mesh_.num_tets(); ++e) {
    const Tet& t = mesh_.tets[e];
    const Mat3 g = edge_frame(positions[t[0]], positions[t[1]], positions[t[2]]);
    if (!g.allFinite()) {  // collapsed edge: keep the previous rotation
      ++fallbacks;
      continue;
    }
    rotations[e] = g * rest_frame_[e].transpose();
  }
  stats_.fallbacks = fallbacks;
}

RotationMethodTraits qr_traits() {
  return {.name = "qr",
          .make = extractor_maker<GramSchmidtFrameExtractor>(),
          .tangent = TangentFamily::GramSchmidt};
}

}  // namespace corofem
