#pragma once
// energy_newton_rotation for kNewtonLanes elements at once, in structure-of-arrays form: every
// quantity of the Newton iteration (N, q, lambda, the gradient, the Hessian's Cholesky factor) is
// an array over the lanes, so the compiler vectorizes across elements and one element's latency
// chain (a 4x4 Cholesky and two solves per step) overlaps its neighbours'. A lane's arithmetic is
// its own: its result does not depend on the other lanes. The extractor's batch does everything
// around Newton across lanes too (the moments S and a from the deformed vertices, the start from
// the warm rotation, the rotation matrix out), with no per-element Eigen round trip. Two forms,
// chosen at run time with the block kernels (sparse/block_kernels.hpp): the portable one and the
// AVX2/FMA one (one 4-lane vector instruction per lane loop; the FMA rounds once where the
// portable form rounds twice, so the two agree to round-off).
#include <cstdint>
#include <vector>

#include "rotation/energy_rotation.hpp"

namespace corofem {

inline constexpr int kNewtonLanes = 4;

/// For every lane the contract of energy_newton_rotation(s, a, warm, tolerance, max_iterations).
/// Lanes whose step meets a Hessian that is not positive definite or a non-finite step, or that
/// do not converge, are handed to energy_newton_rotation itself (its LU step and exact fallback).
void energy_newton_rotations(const Mat3 (&s)[kNewtonLanes], const double (&a)[kNewtonLanes],
                             const Mat3 (&warm)[kNewtonLanes], double tolerance, int max_iterations,
                             NewtonOutcome (&out)[kNewtonLanes]);

/// What the extractor's batches read: the mesh, its moment arms, the deformed positions.
struct NewtonBatchInput {
  const Tet* tets;
  const MomentArms* rest;
  const Vec3* positions;
  double tolerance;
  int max_iterations;
};

struct NewtonBatchCounts {
  int fallbacks = 0;  ///< elements the exact minimizer answered (energy_newton_rotation)
  int inverted = 0;   ///< elements with det S <= 0
};

/// Elements [first, first + lanes), lanes <= kNewtonLanes: rotations[e] holds the warm start on
/// entry and the rotation (energy_newton_rotation's contract, deformed_moment's S and a) on exit;
/// iterations[e] the Newton steps taken.
NewtonBatchCounts energy_newton_batch(const NewtonBatchInput& in, int first, int lanes,
                                      std::vector<Mat3>& rotations, std::uint8_t* iterations);

}  // namespace corofem
