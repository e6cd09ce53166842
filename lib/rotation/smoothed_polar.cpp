#include "rotation/smoothed_polar.hpp"

#include "core/threads.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {

SmoothedPolarExtractor::SmoothedPolarExtractor(const TetMesh& mesh, const Parameters& params)
    : RotationExtractor(RotationMethod::PolarSmoothed),
      mesh_(mesh),
      passes_(static_cast<int>(params.integer("smoothing_passes"))),
      rest_edge_inverse_(rest_edge_inverses(mesh)),
      rings_(element_one_rings(mesh)) {
  volume_.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets)
    volume_.push_back(
        signed_volume(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]));
}

void SmoothedPolarExtractor::extract(const std::vector<Vec3>& positions,
                                     std::vector<Mat3>& rotations) {
  const int nt = mesh_.num_tets();
  stats_.iterations.assign(nt, 0);
  std::vector<Eigen::Vector4d> q(nt), averaged(nt);
#pragma omp parallel for schedule(static) num_threads(threads_for(nt))
  for (int e = 0; e < nt; ++e) {
    const Mat3 r = polar_rotation(
        deformation_gradient(rest_edge_inverse_[e], positions, mesh_.tets[e]), rotations[e]);
    q[e] = to_quaternion(r).coeffs();  // (x, y, z, w)
  }
  for (int pass = 0; pass < passes_; ++pass) {
#pragma omp parallel for schedule(static) num_threads(threads_for(nt))
    for (int e = 0; e < nt; ++e) {
      Eigen::Vector4d sum = Eigen::Vector4d::Zero();
      for (int k = rings_.start[e]; k < rings_.start[e + 1]; ++k) {
        const int n = rings_.elements[k];
        sum += (q[e].dot(q[n]) < 0 ? -volume_[n] : volume_[n]) * q[n];
      }
      averaged[e] = sum.normalized();
    }
    q.swap(averaged);
  }
#pragma omp parallel for schedule(static) num_threads(threads_for(nt))
  for (int e = 0; e < nt; ++e) rotations[e] = Eigen::Quaterniond(q[e]).toRotationMatrix();
}

RotationMethodTraits polar_smoothed_traits() {
  return {.name = "polar-smoothed",
          .make = extractor_maker<SmoothedPolarExtractor>(),
          .parameters = {{.key = "smoothing_passes",
                          .kind = ParameterSpec::Kind::Integer,
                          .fallback = 1LL,
                          .min = 0,
                          .max = 100,
                          .meaning = "passes of volume-weighted 1-ring quaternion averaging"}},
          .tangent = TangentFamily::PolarOfF,
          .tangent_exact = false,  // the neighbours' coupling is left out
          .halo_rings = [](const Parameters& params) {
            return static_cast<int>(params.integer("smoothing_passes"));
          }};
}

}  // namespace corofem
