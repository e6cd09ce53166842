#pragma once
// Unit quaternions (w, x, y, z) of rotation matrices, sign fixed to w >= 0, and the angle between
// two rotations.
#include <Eigen/Geometry>

#include "element/element_stiffness.hpp"

namespace corofem {

/// Quaternion of a proper rotation; for a reflection (det -1) that of -Q, the nearest rotation
/// sharing its axis, so that records stay well-defined (the reflection is reported separately).
Eigen::Quaterniond to_quaternion(const Mat3& q);

/// Angle (rad) of the rotation between rotations a and b, from |a - b|_F = 2 sqrt(2) sin(theta/2);
/// acos of the trace would lose half the digits near 0 (it resolves no better than 2e-8 rad).
double angle_between(const Mat3& a, const Mat3& b);

}  // namespace corofem
