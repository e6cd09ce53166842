#include "rotation/polar_decomposition.hpp"

#include <Eigen/LU>
#include <cmath>

#include "core/threads.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {

Mat3 polar_rotation(const Mat3& f, const Mat3& fallback, int* iterations) {
  Mat3 x = f;
  if (iterations) *iterations = 0;
  double norm = x.norm();
  for (int it = 0; it < 30; ++it) {
    const double det = x.determinant();
    if (!std::isfinite(det) || std::abs(det) <= 1e-14 * norm * norm * norm) {
      if (iterations) *iterations = -1;
      return fallback;
    }
    if (iterations) *iterations = it + 1;
    // X^{-T} = cofactor(X) / det X.
    Mat3 inv_t;
    inv_t.col(0) = x.col(1).cross(x.col(2));
    inv_t.col(1) = x.col(2).cross(x.col(0));
    inv_t.col(2) = x.col(0).cross(x.col(1));
    inv_t /= det;
    // Frobenius-norm scaling gamma = sqrt(|X^-1| / |X|) (Higham 1986) speeds up the first steps.
    const double gamma = std::sqrt(inv_t.norm() / norm);
    const Mat3 next = 0.5 * (gamma * x + inv_t / gamma);
    const double change = (next - x).norm();
    x = next;
    norm = x.norm();
    if (change <= 1e-15 * norm) break;
  }
  return x;
}

PolarExtractor::PolarExtractor(const TetMesh& mesh)
    : RotationExtractor(RotationMethod::Polar),
      mesh_(mesh),
      rest_edge_inverse_(rest_edge_inverses(mesh)) {}

void PolarExtractor::extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) {
  stats_.iterations.resize(mesh_.tets.size());
  int fallbacks = 0;
#pragma omp parallel for schedule(static) reduction(+ : fallbacks) num_threads(threads_for(mesh_.num_tets()))
  for (int e = 0; e < mesh_.num_tets(); ++e) {
    int iterations = 0;
    rotations[e] =
        polar_rotation(deformation_gradient(rest_edge_inverse_[e], positions, mesh_.tets[e]),
                       rotations[e], &iterations);
    stats_.iterations[e] = static_cast<std::uint8_t>(iterations);
    fallbacks += iterations < 0;
  }
  stats_.fallbacks = fallbacks;
}

void IdentityExtractor::extract(const std::vector<Vec3>&, std::vector<Mat3>& rotations) {
  stats_.iterations.assign(rotations.size(), 0);
  for (Mat3& q : rotations) q.setIdentity();
}

RotationMethodTraits polar_traits() {
  return {.name = "polar",
          .make = extractor_maker<PolarExtractor>(),
          .tangent = TangentFamily::PolarOfF,
          .force_has_potential = true,
          .in_smoke = true};
}

RotationMethodTraits identity_traits() {
  return {.name = "none",
          .make = [](const TetMesh&, const Parameters&) -> std::unique_ptr<RotationExtractor> {
            return std::make_unique<IdentityExtractor>();
          },
          .tangent = TangentFamily::Identity,
          .force_has_potential = true,
          .compared = false};
}

}  // namespace corofem
