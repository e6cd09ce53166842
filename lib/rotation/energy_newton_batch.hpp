#pragma once
// energy_newton_rotation for kNewtonLanes elements at once, in structure-of-arrays form: every
// quantity of the Newton iteration (N, q, lambda, the gradient, the Hessian's Cholesky factor) is
// an array over the lanes, so the compiler vectorizes across elements and one element's latency
// chain (a 4x4 Cholesky and two solves per step) overlaps its neighbours'. A lane's arithmetic is
// its own: its result does not depend on the other lanes.
#include "rotation/energy_rotation.hpp"

namespace corofem {

inline constexpr int kNewtonLanes = 4;

/// For every lane the contract of energy_newton_rotation(s, a, warm, tolerance, max_iterations).
/// Lanes whose step meets a Hessian that is not positive definite or a non-finite step, or that
/// do not converge, are handed to energy_newton_rotation itself (its LU step and exact fallback).
void energy_newton_rotations(const Mat3 (&s)[kNewtonLanes], const double (&a)[kNewtonLanes],
                             const Mat3 (&warm)[kNewtonLanes], double tolerance, int max_iterations,
                             NewtonOutcome (&out)[kNewtonLanes]);

}  // namespace corofem
