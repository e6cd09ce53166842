#include "rotation/polar_decomposition.hpp"

#include <Eigen/LU>
#include <cmath>

namespace corofem {

Mat3 polar_rotation(const Mat3& f, const Mat3& fallback) {
  Mat3 x = f;
  for (int it = 0; it < 30; ++it) {
    const double det = x.determinant();
    if (!std::isfinite(det) || std::abs(det) <= 1e-14 * std::pow(x.norm(), 3)) return fallback;
    const Mat3 inv_t = x.inverse().transpose();
    // Frobenius-norm scaling gamma = sqrt(|X^-1| / |X|) (Higham 1986) speeds up the first steps.
    const double gamma = std::sqrt(inv_t.norm() / x.norm());
    const Mat3 next = 0.5 * (gamma * x + inv_t / gamma);
    const double change = (next - x).norm();
    x = next;
    if (change <= 1e-15 * x.norm()) break;
  }
  return x;
}

PolarExtractor::PolarExtractor(const TetMesh& mesh) : mesh_(mesh) {
  rest_edge_inverse_.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets)
    rest_edge_inverse_.push_back(
        rest_edge_inverse(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]));
}

void PolarExtractor::extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) {
  for (int e = 0; e < mesh_.num_tets(); ++e)
    rotations[e] = polar_rotation(
        deformation_gradient(rest_edge_inverse_[e], positions, mesh_.tets[e]), rotations[e]);
}

void IdentityExtractor::extract(const std::vector<Vec3>&, std::vector<Mat3>& rotations) {
  for (Mat3& q : rotations) q.setIdentity();
}

}  // namespace corofem
