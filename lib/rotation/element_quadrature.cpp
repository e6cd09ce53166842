#include "rotation/element_quadrature.hpp"

namespace corofem {

QuadraturePoints quadrature_points(const std::array<Vec3, 4>& v, double volume) {
  const Vec3 centroid = 0.25 * (v[0] + v[1] + v[2] + v[3]);
  QuadraturePoints q;
  for (int g = 0; g < 4; ++g) {
    Vec3 point = Vec3::Zero();
    for (int a = 0; a < 4; ++a) point += (a == g ? kQuadratureA : kQuadratureB) * v[a];
    q.offset[g] = point - centroid;
  }
  q.weight = volume / 4;
  return q;
}

MomentArms moment_arms(const QuadraturePoints& rest) {
  MomentArms m;
  for (int v = 0; v < 4; ++v) m.h[v] = rest.weight * (kQuadratureA - kQuadratureB) * rest.offset[v];
  m.c = rest.weight * (kQuadratureA - kQuadratureB) * (kQuadratureA - kQuadratureB);
  return m;
}

double rotation_energy(const Mat3& q, const QuadraturePoints& rest,
                       const QuadraturePoints& deformed) {
  double e = 0;
  for (int g = 0; g < 4; ++g)
    e += rest.weight * (q.transpose() * deformed.offset[g] - rest.offset[g]).squaredNorm();
  return e;
}

}  // namespace corofem
