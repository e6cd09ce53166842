#include "rotation/svd_rotation.hpp"

#include "core/threads.hpp"
#include "rotation/rotation_factor.hpp"

namespace corofem {

std::vector<Mat3> rest_edge_inverses(const TetMesh& mesh) {
  std::vector<Mat3> inverses;
  inverses.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets)
    inverses.push_back(
        rest_edge_inverse(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]));
  return inverses;
}

InversionAwareSvdExtractor::InversionAwareSvdExtractor(const TetMesh& mesh)
    : RotationExtractor(RotationMethod::PolarFixed),
      mesh_(mesh),
      rest_edge_inverse_(rest_edge_inverses(mesh)) {}

void InversionAwareSvdExtractor::extract(const std::vector<Vec3>& positions,
                                         std::vector<Mat3>& rotations) {
  stats_.iterations.assign(mesh_.tets.size(), 0);
#pragma omp parallel for schedule(static) num_threads(threads_for(mesh_.num_tets()))
  for (int e = 0; e < mesh_.num_tets(); ++e)
    rotations[e] =
        rotation_factor(deformation_gradient(rest_edge_inverse_[e], positions, mesh_.tets[e]));
}

RotationMethodTraits polar_fixed_traits() {
  return {.name = "polar-fixed",
          .make = extractor_maker<InversionAwareSvdExtractor>(),
          .tangent = TangentFamily::PolarOfF,
          .force_has_potential = true};  // its reflection moved into the stretch
}

}  // namespace corofem
