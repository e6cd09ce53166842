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

/// One batch of elements in structure-of-arrays form: S (row-major), a, and q, which holds the
/// start and, where `solved`, the result; lanes not solved go to energy_newton_rotation.
struct NewtonLanes {
  double s[9][W];
  double a[W];
  double q[4][W];
  int iterations[W];
  bool solved[W];
};

/// One number per lane: GCC's vector extension, so that every operation below is one 4-wide
/// instruction in the AVX2 form (two 2-wide ones in the portable form) whatever the compiler's
/// loop vectorizer makes of it; comparisons give lane masks, ?: selects lane by lane.
// Every function taking or returning Lanes is forced inline: no call crosses an ABI boundary, so
// GCC's note that the portable form passes 32-byte vectors differently does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
using Lanes = double __attribute__((vector_size(8 * W)));
using Mask = long long __attribute__((vector_size(8 * W)));
static_assert(sizeof(Lanes) == sizeof(double[W]));

COROFEM_LANES_INLINE Lanes load(const double (&x)[W]) {
  Lanes v;
  __builtin_memcpy(&v, x, sizeof v);
  return v;
}
COROFEM_LANES_INLINE Lanes splat(double s) { return Lanes{} + s; }
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
    y[r] = m.m[kOff[r][0]] * x[0] + m.m[kOff[r][1]] * x[1] + m.m[kOff[r][2]] * x[2] + m.m[kOff[r][3]] * x[3];
}

/// N = horn_matrix(S^T) per lane: q^T N q = tr(R(q)^T S^T).
COROFEM_LANES_INLINE void horn_lanes(const double (&s)[9][W], Sym4& n) {
  const Lanes s00 = load(s[0]), s01 = load(s[1]), s02 = load(s[2]), s10 = load(s[3]), s11 = load(s[4]),
              s12 = load(s[5]), s20 = load(s[6]), s21 = load(s[7]), s22 = load(s[8]);
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
COROFEM_LANES_INLINE void hessian(const Sym4& n, const Lanes (&q)[4], Lanes q2, Lanes a, Lanes lambda, Sym4& h) {
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
  Lanes q[4], nq[4], grad[4], hg[4], hq[4];
  for (int r = 0; r < 4; ++r) q[r] = load(p.q[r]);
  const Lanes a = load(p.a);
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
    const Mask within = sqrt_lanes(g2) / (4 * a) + (constraint < 0 ? -constraint : constraint) < tolerance;
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
    handed_over |= active & ~step;  // not the definite case, or no finite step: the scalar routine decides
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
  for (int l = 0; l < W; ++l) {
    for (int r = 0; r < 4; ++r) p.q[r][l] = q[r][l];
    p.solved[l] = converged[l] != 0 && handed_over[l] == 0;
    p.iterations[l] = static_cast<int>(iterations[l]);
  }
}

/// Lanes from separate (S, a, warm) triples: the batched Newton and its outcomes.
COROFEM_LANES_INLINE void rotations_of_triples(const Mat3 (&s)[W], const double (&a)[W], const Mat3 (&warm)[W],
                                               double tolerance, int max_iterations, NewtonOutcome (&out)[W]) {
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
    if (!p.solved[l]) {
      out[l] = energy_newton_rotation(s[l], a[l], warm[l], tolerance, max_iterations);
      continue;
    }
    out[l].rotation = newton_rotation({p.q[0][l], p.q[1][l], p.q[2][l], p.q[3][l]});
    out[l].iterations = p.iterations[l];
    out[l].fell_back = false;
  }
}

/// One batch of the extractor, read and written in place: the moments S and a of eq. (3) from
/// the deformed vertices (deformed_moment), the start from the warm rotation, Newton, and the
/// rotation and inversion sign out, all across lanes.
COROFEM_LANES_INLINE NewtonBatchCounts extract_lanes(const NewtonBatchInput& in, int first, int lanes,
                                                     std::vector<Mat3>& rotations, std::uint8_t* iterations) {
  double pos[4][3][W], arm[4][3][W], c[W], warm[9][W];
  for (int l = 0; l < W; ++l) {
    const int e = first + std::min(l, lanes - 1);  // the last batch repeats its last element
    const Tet& t = in.tets[e];
    const MomentArms& rest = in.rest[e];
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) {
        pos[v][k][l] = in.positions[t[v]][k];
        arm[v][k][l] = rest.h[v][k];
      }
    c[l] = rest.c;
    const double* m = rotations[e].data();  // column-major Q: Q^T row by row
    for (int k = 0; k < 9; ++k) warm[k][l] = m[k];
  }
  NewtonLanes p;
  double det[W];
  for (int l = 0; l < W; ++l) {
    double mean[3], spread = 0;
    for (int k = 0; k < 3; ++k) mean[k] = 0.25 * (pos[0][k][l] + pos[1][k][l] + pos[2][k][l] + pos[3][k][l]);
    for (int k = 0; k < 9; ++k) p.s[k][l] = 0;
    for (int v = 0; v < 4; ++v) {
      double z[3];
      for (int k = 0; k < 3; ++k) z[k] = pos[v][k][l] - mean[k];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) p.s[3 * i + j][l] += z[i] * arm[v][j][l];
      spread += z[0] * z[0] + z[1] * z[1] + z[2] * z[2];
    }
    p.a[l] = c[l] * spread;
    det[l] = p.s[0][l] * (p.s[4][l] * p.s[8][l] - p.s[5][l] * p.s[7][l]) -
             p.s[1][l] * (p.s[3][l] * p.s[8][l] - p.s[5][l] * p.s[6][l]) +
             p.s[2][l] * (p.s[3][l] * p.s[7][l] - p.s[4][l] * p.s[6][l]);
    double m[9], q[4];
    for (int k = 0; k < 9; ++k) m[k] = warm[k][l];
    quaternion_of_rotation(m, q);
    for (int r = 0; r < 4; ++r) p.q[r][l] = q[r];
  }
  newton_lanes(p, in.tolerance, in.max_iterations);
  double out[9][W];
  for (int l = 0; l < W; ++l) {
    double q[4], m[9];
    for (int r = 0; r < 4; ++r) q[r] = p.q[r][l];
    rotation_of_quaternion(q, m);  // R(q) row-major: Q = R^T column-major
    for (int k = 0; k < 9; ++k) out[k][l] = m[k];
  }
  NewtonBatchCounts counts;
  for (int l = 0; l < lanes; ++l) {
    const int e = first + l;
    counts.inverted += det[l] <= 0;
    if (!p.solved[l]) {
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

void rotations_of_triples_scalar(const Mat3 (&s)[W], const double (&a)[W], const Mat3 (&warm)[W], double tolerance,
                                 int max_iterations, NewtonOutcome (&out)[W]) {
  rotations_of_triples(s, a, warm, tolerance, max_iterations, out);
}
NewtonBatchCounts extract_lanes_scalar(const NewtonBatchInput& in, int first, int lanes,
                                       std::vector<Mat3>& rotations, std::uint8_t* iterations) {
  return extract_lanes(in, first, lanes, rotations, iterations);
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void rotations_of_triples_avx2(const Mat3 (&s)[W], const double (&a)[W],
                                                                   const Mat3 (&warm)[W], double tolerance,
                                                                   int max_iterations, NewtonOutcome (&out)[W]) {
  rotations_of_triples(s, a, warm, tolerance, max_iterations, out);
}
__attribute__((target("avx2,fma"))) NewtonBatchCounts extract_lanes_avx2(const NewtonBatchInput& in, int first,
                                                                         int lanes, std::vector<Mat3>& rotations,
                                                                         std::uint8_t* iterations) {
  return extract_lanes(in, first, lanes, rotations, iterations);
}
#endif

}  // namespace

void energy_newton_rotations(const Mat3 (&s)[kNewtonLanes], const double (&a)[kNewtonLanes],
                             const Mat3 (&warm)[kNewtonLanes], double tolerance, int max_iterations,
                             NewtonOutcome (&out)[kNewtonLanes]) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels()) return rotations_of_triples_avx2(s, a, warm, tolerance, max_iterations, out);
#endif
  rotations_of_triples_scalar(s, a, warm, tolerance, max_iterations, out);
}

NewtonBatchCounts energy_newton_batch(const NewtonBatchInput& in, int first, int lanes, std::vector<Mat3>& rotations,
                                      std::uint8_t* iterations) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels()) return extract_lanes_avx2(in, first, lanes, rotations, iterations);
#endif
  return extract_lanes_scalar(in, first, lanes, rotations, iterations);
}

}  // namespace corofem
