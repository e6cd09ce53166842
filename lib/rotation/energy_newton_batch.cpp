// Every function taking or returning Lanes (below) is forced inline, and so is the header's
// quaternion_of_rotation on them: no call crosses an ABI boundary, so GCC's note that the portable
// form passes 32-byte vectors differently does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "rotation/energy_newton_batch.hpp"

#include <algorithm>
#include <cmath>

#include "sparse/block_kernels.hpp"

// Every helper is forced inline so that it is compiled into each of the two forms below, the
// portable one and the AVX2/FMA one (a lane operation is then one vector instruction); a helper
// compiled once for the baseline ISA would run 2-wide in the AVX2 form.
#define COROFEM_LANES_INLINE __attribute__((always_inline)) inline

namespace corofem {
namespace {

constexpr int W = kNewtonLanes;

/// One number per lane: GCC's vector extension, so that every operation below is one 4-wide
/// instruction in the AVX2 form (two 2-wide ones in the portable form) whatever the compiler's
/// loop vectorizer makes of it; comparisons give lane masks, ?: selects lane by lane.
using Lanes = double __attribute__((vector_size(8 * W)));
using Mask = long long __attribute__((vector_size(8 * W)));
static_assert(sizeof(Lanes) == sizeof(double[W]));
static_assert(W == 4, "extract_lanes puts its lanes together four at a time");

/// One batch of elements in structure-of-arrays form: S (row-major), a, and q, which holds the
/// start and, where `solved`, the result; lanes not solved go to energy_newton_rotation.
struct NewtonLanes {
  Lanes s[9];
  Lanes a;
  Lanes q[4];
  Lanes iterations;
  Mask solved;
};

COROFEM_LANES_INLINE Lanes splat(double s) {
  return Lanes{} + s;
}
COROFEM_LANES_INLINE Lanes sqrt_lanes(Lanes x) {
  for (int l = 0; l < W; ++l) x[l] = std::sqrt(x[l]);
  return x;
}
COROFEM_LANES_INLINE bool any_lane(Mask m) {
  long long any = 0;
  for (int l = 0; l < W; ++l) any |= m[l];
  return any != 0;
}

/// A symmetric 4x4 matrix per lane: its 10 entries (00 11 22 33 01 02 03 12 13 23).
struct Sym4 {
  Lanes m[10];
};
constexpr int kOff[4][4] = {{0, 4, 5, 6}, {4, 1, 7, 8}, {5, 7, 2, 9}, {6, 8, 9, 3}};

COROFEM_LANES_INLINE Lanes dot(const Lanes (&x)[4], const Lanes (&y)[4]) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2] + x[3] * y[3];
}

/// y = M x per lane.
COROFEM_LANES_INLINE void multiply(const Sym4& m, const Lanes (&x)[4], Lanes (&y)[4]) {
  for (int r = 0; r < 4; ++r)
    y[r] = m.m[kOff[r][0]] * x[0] + m.m[kOff[r][1]] * x[1] + m.m[kOff[r][2]] * x[2] +
           m.m[kOff[r][3]] * x[3];
}

/// N = horn_matrix(S^T) per lane: q^T N q = tr(R(q)^T S^T).
COROFEM_LANES_INLINE void horn_lanes(const Lanes (&s)[9], Sym4& n) {
  const Lanes s00 = s[0], s01 = s[1], s02 = s[2], s10 = s[3], s11 = s[4], s12 = s[5], s20 = s[6],
              s21 = s[7], s22 = s[8];
  n.m[0] = s00 + s11 + s22;
  n.m[1] = s00 - s11 - s22;
  n.m[2] = -s00 + s11 - s22;
  n.m[3] = -s00 - s11 + s22;
  n.m[4] = s12 - s21;
  n.m[5] = s20 - s02;
  n.m[6] = s01 - s10;
  n.m[7] = s10 + s01;
  n.m[8] = s20 + s02;
  n.m[9] = s21 + s12;
}

/// Cholesky factor L (lower, with the inverse of its diagonal) per lane; ok is false in a lane
/// where a pivot is not positive (that lane's factor is then meaningless).
struct Cholesky4Lanes {
  Lanes l[4][4];
  Lanes inverse_diagonal[4];
  Mask ok;
};

COROFEM_LANES_INLINE void factor(const Sym4& h, Cholesky4Lanes& f) {
  f.ok = Mask{} - 1;
  for (int j = 0; j < 4; ++j) {
    Lanes d = h.m[kOff[j][j]];
    for (int k = 0; k < j; ++k) d -= f.l[j][k] * f.l[j][k];
    const Mask positive = d > 0;
    f.ok &= positive;
    f.l[j][j] = sqrt_lanes(positive ? d : splat(1.0));
    f.inverse_diagonal[j] = 1 / f.l[j][j];
    for (int i = j + 1; i < 4; ++i) {
      Lanes v = h.m[kOff[i][j]];
      for (int k = 0; k < j; ++k) v -= f.l[i][k] * f.l[j][k];
      f.l[i][j] = v * f.inverse_diagonal[j];
    }
  }
}

/// x = H^-1 b per lane: L y = b, L^T x = y.
COROFEM_LANES_INLINE void solve(const Cholesky4Lanes& f, const Lanes (&b)[4], Lanes (&x)[4]) {
  Lanes y[4];
  for (int i = 0; i < 4; ++i) {
    Lanes v = b[i];
    for (int k = 0; k < i; ++k) v -= f.l[i][k] * y[k];
    y[i] = v * f.inverse_diagonal[i];
  }
  for (int i = 3; i >= 0; --i) {
    Lanes v = y[i];
    for (int k = i + 1; k < 4; ++k) v -= f.l[k][i] * x[k];
    x[i] = v * f.inverse_diagonal[i];
  }
}

/// The Hessian 4a(|q|^2 I + 2 q q^T) - 4N + 2 lambda I per lane (eq. 7).
COROFEM_LANES_INLINE void hessian(const Sym4& n, const Lanes (&q)[4], Lanes q2, Lanes a,
                                  Lanes lambda, Sym4& h) {
  for (int r = 0; r < 4; ++r)
    for (int c = r; c < 4; ++c) {
      const Lanes outer = 4 * a * (2 * q[r] * q[c]) - 4 * n.m[kOff[r][c]];
      h.m[kOff[r][c]] = r == c ? 4 * a * q2 + outer + 2 * lambda : outer;
    }
}

/// Newton on (q, lambda) in every lane, the contract of energy_newton_rotation for its definite
/// case. Lane states are masks and every update a select; a lane that stops keeps its q.
COROFEM_LANES_INLINE void newton_lanes(NewtonLanes& p, double tolerance, int max_iterations) {
  Sym4 n, h;
  Cholesky4Lanes llt;
  Lanes q[4] = {p.q[0], p.q[1], p.q[2], p.q[3]}, nq[4], grad[4], hg[4], hq[4];
  const Lanes a = p.a;
  horn_lanes(p.s, n);
  multiply(n, q, nq);
  Lanes lambda = 2 * dot(q, nq) - 2 * a * dot(q, q), q2 = {}, iterations = {};
  Mask active = Mask{} - 1, converged = {}, handed_over = {};
  for (int it = 0;; ++it) {
    // Gradient of eq. (5) and constraint of eq. (6); lanes within the tolerance stop.
    if (it > 0) multiply(n, q, nq);
    q2 = dot(q, q);
    Lanes g2 = {};
    for (int r = 0; r < 4; ++r) {
      grad[r] = 4 * a * q2 * q[r] - 4 * nq[r] + 2 * lambda * q[r];
      g2 += grad[r] * grad[r];
    }
    const Lanes constraint = q2 - 1;
    const Mask within =
        sqrt_lanes(g2) / (4 * a) + (constraint < 0 ? -constraint : constraint) < tolerance;
    converged |= active & within;
    active &= ~within;
    if (it == max_iterations) active = Mask{};
    if (!any_lane(active)) break;
    // The bordered Newton step of eqs. (7), (8) by the Schur complement in dl.
    hessian(n, q, q2, a, lambda, h);
    factor(h, llt);
    solve(llt, grad, hg);
    solve(llt, q, hq);
    const Lanes dl = (constraint - 2 * dot(q, hg)) / (4 * dot(q, hq));
    Lanes dq[4], check = dl;  // the sum of the step's entries: not finite if any entry is not
    for (int r = 0; r < 4; ++r) {
      dq[r] = -(hg[r] + 2 * dl * hq[r]);
      check += dq[r];
    }
    const Mask step = active & llt.ok & (check - check == 0);
    handed_over |=
        active & ~step;  // not the definite case, or no finite step: the scalar routine decides
    for (int r = 0; r < 4; ++r) q[r] = step ? q[r] + dq[r] : q[r];
    lambda = step ? lambda + dl : lambda;
    iterations = step ? splat(it + 1) : iterations;
    active = step;
  }
  // A lane that converged without a step has not shown a definite Hessian yet: a minimizer has
  // one, a saddle does not (energy_rotation.hpp).
  if (any_lane(converged & (iterations == 0))) {
    hessian(n, q, q2, a, lambda, h);  // q2 is the last gradient's, of the final q
    factor(h, llt);
    converged &= (iterations > 0) | llt.ok;
  }
  for (int r = 0; r < 4; ++r) p.q[r] = q[r];
  p.solved = converged & ~handed_over;
  p.iterations = iterations;
}

/// Lanes from separate (S, a, warm) triples: the batched Newton and its outcomes.
COROFEM_LANES_INLINE void rotations_of_triples(const Mat3 (&s)[W], const double (&a)[W],
                                               const Mat3 (&warm)[W], double tolerance,
                                               int max_iterations, NewtonOutcome (&out)[W]) {
  NewtonLanes p;
  for (int l = 0; l < W; ++l) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.s[3 * i + j][l] = s[l](i, j);
    p.a[l] = a[l];
    const Eigen::Vector4d start = newton_start(warm[l]);
    for (int r = 0; r < 4; ++r) p.q[r][l] = start[r];
  }
  newton_lanes(p, tolerance, max_iterations);
  for (int l = 0; l < W; ++l) {
    if (p.solved[l] == 0) {
      out[l] = energy_newton_rotation(s[l], a[l], warm[l], tolerance, max_iterations);
      continue;
    }
    out[l].rotation = newton_rotation({p.q[0][l], p.q[1][l], p.q[2][l], p.q[3][l]});
    out[l].iterations = static_cast<int>(p.iterations[l]);
    out[l].fell_back = false;
  }
}

/// One batch of the extractor, read and written in place: the moments S and a of eq. (3) from
/// the deformed vertices (deformed_moment), the start from the warm rotation, Newton, and the
/// rotation and inversion sign out, all across lanes.
COROFEM_LANES_INLINE NewtonBatchCounts extract_lanes(const NewtonBatchInput& in, int first,
                                                     int lanes, std::vector<Mat3>& rotations,
                                                     std::uint8_t* iterations) {
  // Lane l is element first + l (the last batch repeats its last element). The lanes are put
  // together from the elements' numbers directly, in registers.
  const Tet* tet[W];
  const MomentArms* rest[W];
  const double* warm_of[W];  // column-major Q: Q^T row by row
  for (int l = 0; l < W; ++l) {
    const int e = first + std::min(l, lanes - 1);
    tet[l] = &in.tets[e];
    rest[l] = &in.rest[e];
    warm_of[l] = rotations[e].data();
  }
  NewtonLanes p;
  Lanes pos[4][3], arm[4][3], warm[9];
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k) {
      pos[v][k] = Lanes{in.positions[(*tet[0])[v]][k], in.positions[(*tet[1])[v]][k],
                        in.positions[(*tet[2])[v]][k], in.positions[(*tet[3])[v]][k]};
      arm[v][k] = Lanes{rest[0]->h[v][k], rest[1]->h[v][k], rest[2]->h[v][k], rest[3]->h[v][k]};
    }
  for (int k = 0; k < 9; ++k)
    warm[k] = Lanes{warm_of[0][k], warm_of[1][k], warm_of[2][k], warm_of[3][k]};
  // deformed_moment across lanes: S = sum_v z_v h_v^T, a = c sum_v |z_v|^2, z from the centroid.
  Lanes mean[3], spread = {};
  for (int k = 0; k < 3; ++k) mean[k] = 0.25 * (pos[0][k] + pos[1][k] + pos[2][k] + pos[3][k]);
  for (int k = 0; k < 9; ++k) p.s[k] = Lanes{};
  for (int v = 0; v < 4; ++v) {
    const Lanes z[3] = {pos[v][0] - mean[0], pos[v][1] - mean[1], pos[v][2] - mean[2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.s[3 * i + j] += z[i] * arm[v][j];
    spread += z[0] * z[0] + z[1] * z[1] + z[2] * z[2];
  }
  p.a = Lanes{rest[0]->c, rest[1]->c, rest[2]->c, rest[3]->c} * spread;
  const Lanes det = p.s[0] * (p.s[4] * p.s[8] - p.s[5] * p.s[7]) -
                    p.s[1] * (p.s[3] * p.s[8] - p.s[5] * p.s[6]) +
                    p.s[2] * (p.s[3] * p.s[7] - p.s[4] * p.s[6]);
  quaternion_of_rotation(warm, p.q, sqrt_lanes);
  newton_lanes(p, in.tolerance, in.max_iterations);
  Lanes out[9];
  rotation_of_quaternion(p.q, out);  // R(q) row-major: Q = R^T column-major
  NewtonBatchCounts counts;
  for (int l = 0; l < lanes; ++l) {
    const int e = first + l;
    counts.inverted += det[l] <= 0;
    if (p.solved[l] == 0) {
      Mat3 s, w;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s(i, j) = p.s[3 * i + j][l];
      for (int k = 0; k < 9; ++k) w.data()[k] = warm[k][l];
      const NewtonOutcome r = energy_newton_rotation(s, p.a[l], w, in.tolerance, in.max_iterations);
      rotations[e] = r.rotation;
      iterations[e] = static_cast<std::uint8_t>(r.iterations);
      counts.fallbacks += r.fell_back;
      continue;
    }
    double* m = rotations[e].data();
    for (int k = 0; k < 9; ++k) m[k] = out[k][l];
    iterations[e] = static_cast<std::uint8_t>(p.iterations[l]);
  }
  return counts;
}

void rotations_of_triples_scalar(const Mat3 (&s)[W], const double (&a)[W], const Mat3 (&warm)[W],
                                 double tolerance, int max_iterations, NewtonOutcome (&out)[W]) {
  rotations_of_triples(s, a, warm, tolerance, max_iterations, out);
}
NewtonBatchCounts extract_lanes_scalar(const NewtonBatchInput& in, int first, int lanes,
                                       std::vector<Mat3>& rotations, std::uint8_t* iterations) {
  return extract_lanes(in, first, lanes, rotations, iterations);
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void rotations_of_triples_avx2(
    const Mat3 (&s)[W], const double (&a)[W], const Mat3 (&warm)[W], double tolerance,
    int max_iterations, NewtonOutcome (&out)[W]) {
  rotations_of_triples(s, a, warm, tolerance, max_iterations, out);
}
__attribute__((target("avx2,fma"))) NewtonBatchCounts extract_lanes_avx2(
    const NewtonBatchInput& in, int first, int lanes, std::vector<Mat3>& rotations,
    std::uint8_t* iterations) {
  return extract_lanes(in, first, lanes, rotations, iterations);
}
#endif

}  // namespace

void energy_newton_rotations(const Mat3 (&s)[kNewtonLanes], const double (&a)[kNewtonLanes],
                             const Mat3 (&warm)[kNewtonLanes], double tolerance, int max_iterations,
                             NewtonOutcome (&out)[kNewtonLanes]) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels())
    return rotations_of_triples_avx2(s, a, warm, tolerance, max_iterations, out);
#endif
  rotations_of_triples_scalar(s, a, warm, tolerance, max_iterations, out);
}

NewtonBatchCounts energy_newton_batch(const NewtonBatchInput& in, int first, int lanes,
                                      std::vector<Mat3>& rotations, std::uint8_t* iterations) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels()) return extract_lanes_avx2(in, first, lanes, rotations, iterations);
#endif
  return extract_lanes_scalar(in, first, lanes, rotations, iterations);
}

}  // namespace corofem
