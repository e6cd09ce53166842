#include "rotation/rotation_factor.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace corofem {

Mat3 rotation_factor(const Mat3& m) {
  const Eigen::JacobiSVD<Mat3> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3& u = svd.matrixU();
  const Mat3& v = svd.matrixV();
  // A reflection in U V^T is undone on the smallest singular value's pair of vectors.
  const Vec3 signs(1, 1, (u * v.transpose()).determinant() < 0 ? -1 : 1);
  return u * signs.asDiagonal() * v.transpose();
}

}  // namespace corofem
