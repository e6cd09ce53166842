#include "rotation/quaternion.hpp"

#include <Eigen/LU>

namespace corofem {

Eigen::Quaterniond to_quaternion(const Mat3& q) {
  Eigen::Quaterniond quat(q.determinant() < 0 ? Mat3(-q) : q);
  quat.normalize();
  if (quat.w() < 0) quat.coeffs() = -quat.coeffs();
  return quat;
}

}  // namespace corofem
