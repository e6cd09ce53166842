#include "rotation/mueller2016.hpp"

#include <Eigen/Geometry>

#include "core/threads.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {

Mat3 mueller2016_rotation(const Mat3& a, const Mat3& warm, int max_iterations, double tolerance,
                          int& iterations) {
  Eigen::Quaterniond q(warm);
  q.normalize();
  iterations = 0;
  for (int it = 0; it < max_iterations; ++it) {
    const Mat3 r = q.toRotationMatrix();
    const Vec3 numerator =
        r.col(0).cross(a.col(0)) + r.col(1).cross(a.col(1)) + r.col(2).cross(a.col(2));
    const double denominator =
        std::abs(r.col(0).dot(a.col(0)) + r.col(1).dot(a.col(1)) + r.col(2).dot(a.col(2))) + 1e-9;
    const Vec3 omega = numerator / denominator;
    const double angle = omega.norm();
    if (angle < tolerance) break;
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle)) * q;
    q.normalize();
    iterations = it + 1;
  }
  return q.toRotationMatrix();
}

Mueller2016Extractor::Mueller2016Extractor(const TetMesh& mesh, const Parameters& params)
    : RotationExtractor(RotationMethod::Mueller2016),
      mesh_(mesh),
      iterations_(static_cast<int>(params.integer("mueller_iterations"))),
      tolerance_(params.number("mueller_tolerance")),
      rest_edge_inverse_(rest_edge_inverses(mesh)) {}

void Mueller2016Extractor::extract(const std::vector<Vec3>& positions,
                                   std::vector<Mat3>& rotations) {
  stats_.iterations.resize(mesh_.tets.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(mesh_.num_tets()))
  for (int e = 0; e < mesh_.num_tets(); ++e) {
    int iterations = 0;
    rotations[e] =
        mueller2016_rotation(deformation_gradient(rest_edge_inverse_[e], positions, mesh_.tets[e]),
                             rotations[e], iterations_, tolerance_, iterations);
    stats_.iterations[e] = static_cast<std::uint8_t>(iterations);
  }
}

RotationMethodTraits mueller2016_traits() {
  return {.name = "mueller2016",
          .make = extractor_maker<Mueller2016Extractor>(),
          .parameters = {{.key = "mueller_iterations",
                          .kind = ParameterSpec::Kind::Integer,
                          .fallback = 10LL,
                          .min = 1,
                          .max = 200,
                          .meaning = "iterations per element and step (warm-started)"},
                         {.key = "mueller_tolerance",
                          .fallback = 1e-9,
                          .min = kMinTolerance,
                          .max = 0.5,
                          .meaning = "stop at |omega| below this (rad), as Mueller 2016"}},
          .static_tolerances = {"mueller_tolerance"},
          .tangent = TangentFamily::PolarOfF,  // that of the limit it iterates to
          .looser = {{"mueller_iterations", {3, 1}}}};
}

}  // namespace corofem
