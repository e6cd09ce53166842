#pragma once
// The proper rotation factor of a 3x3 matrix: the rotation R maximizing tr(R^T M), which
// minimizes the paper's rotation energy (eq. 3) for M = S = F C, and is polar(F) with inversion
// handled (Irving et al. 2004) for M = F. Its oracles: reference/exact_rotation.hpp (Horn's
// quaternion route and a brute-force search).
#include "core/types.hpp"

namespace corofem {

/// R = U diag(1, 1, det(U V^T)) V^T from the SVD M = U S V^T (singular values descending).
/// Unique unless the two smallest singular values of M are equal with det M < 0 (or M has rank
/// below 2).
Mat3 rotation_factor(const Mat3& m);

}  // namespace corofem
