#pragma once
// The small fixed-size vectors and matrices every layer speaks in.
#include <Eigen/Core>

namespace corofem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

}  // namespace corofem
