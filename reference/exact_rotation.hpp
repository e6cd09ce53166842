#pragma once
// Exact minimizers of the paper's rotation energy (PAPER_NOTES section 2): for a linear tet,
// E_e(Q) = const - 2 tr(Q^T S) with S = F C, so the minimizer is the proper rotation factor of S.
// The production path takes the SVD route (rotation/rotation_factor.hpp); the oracles here are
// Eigen's Jacobi SVD, Horn's quaternion route and a brute-force search that assumes nothing
// about the energy.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>

namespace corofem::reference {

/// argmax over proper rotations of tr(R^T M) by Horn (1987): the unit quaternion q maximizing
/// q^T N q, N the 4x4 symmetric matrix with q^T N q = tr(R(q)^T M) for unit q, i.e. the
/// eigenvector of N's largest eigenvalue. N is built here by polarization from quaternion
/// products, not from Horn's table.
Eigen::Quaterniond rotation_factor_horn(const Eigen::Matrix3d& m);

/// argmax over proper rotations of tr(R^T M) by Eigen's two-sided Jacobi SVD, M = U S V^T:
/// R = U diag(1, 1, det(U V^T)) V^T (the smallest singular value's direction flipped when M's
/// determinant is negative). Shares no code with rotation/: the oracle of its rotation_factor.
Eigen::Matrix3d rotation_factor_svd(const Eigen::Matrix3d& m);

/// Global minimizer of an arbitrary energy over SO(3): `samples` uniformly random rotations
/// (Shoemake's method, fixed seed), then pattern search around the best one with the step halved
/// from 0.1 rad down to 1e-11 rad.
Eigen::Matrix3d brute_force_minimize(const std::function<double(const Eigen::Matrix3d&)>& energy,
                                     int samples = 20000, unsigned seed = 1);

}  // namespace corofem::reference
