#include "rotation/quaternion.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace corofem {

Eigen::Quaterniond to_quaternion(const Mat3& q) {
  Eigen::Quaterniond quat(q.determinant() < 0 ? Mat3(-q) : q);
  quat.normalize();
  if (quat.w() < 0) quat.coeffs() = -quat.coeffs();
  return quat;
}

double angle_between(const Mat3& a, const Mat3& b) {
  return 2 * std::asin(std::min(1.0, (a - b).norm() / (2 * std::sqrt(2.0))));
}

}  // namespace corofem
