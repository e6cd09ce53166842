#pragma once
// Unit quaternions (w, x, y, z) of rotation matrices, sign fixed to w >= 0.
#include <Eigen/Geometry>

#include "fem/element_stiffness.hpp"

namespace corofem {

/// Quaternion of a proper rotation; for a reflection (det -1) that of -Q, the nearest rotation
/// sharing its axis, so that records stay well-defined (the reflection is reported separately).
Eigen::Quaterniond to_quaternion(const Mat3& q);

}  // namespace corofem
