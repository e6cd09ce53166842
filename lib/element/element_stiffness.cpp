#include "element/element_stiffness.hpp"

#include <Eigen/LU>

namespace corofem {

Mat3 rest_edge_inverse(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Mat3 dm;
  dm << x1 - x0, x2 - x0, x3 - x0;
  return dm.inverse();
}

std::array<Vec3, 4> shape_gradients(const Mat3& rest_edge_inverse) {
  std::array<Vec3, 4> g;
  g[1] = rest_edge_inverse.row(0).transpose();
  g[2] = rest_edge_inverse.row(1).transpose();
  g[3] = rest_edge_inverse.row(2).transpose();
  g[0] = -(g[1] + g[2] + g[3]);
  return g;
}

Mat12 element_stiffness(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                        const Material& material) {
  const std::array<Vec3, 4> g = shape_gradients(rest_edge_inverse(x0, x1, x2, x3));
  const double volume = std::abs(signed_volume(x0, x1, x2, x3));
  return gradient_stiffness(g, volume * material.lame_lambda(), volume * material.lame_mu());
}

Mat12 gradient_stiffness(const std::array<Vec3, 4>& g, double lambda_volume, double mu_volume) {
  Mat12 k;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      k.block<3, 3>(3 * a, 3 * b) = lambda_volume * g[a] * g[b].transpose() +
                                    mu_volume * g[b] * g[a].transpose() +
                                    mu_volume * g[a].dot(g[b]) * Mat3::Identity();
  return k;
}

}  // namespace corofem
