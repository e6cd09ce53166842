#include "rotation/energy_newton_batch.hpp"

#include <algorithm>
#include <cmath>

#include "sparse/block_kernels.hpp"

// Every helper is forced inline so that it is compiled into each of the two forms below, the
// portable one and the AVX2/FMA one (a 4-lane loop is then one vector instruction); a helper
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

/// A symmetric 4x4 matrix per lane: its 10 entries (00 11 22 33 01 02 03 12 13 23).
struct Sym4 {
  double m[10][W];
};
constexpr int kOff[4][4] = {{0, 4, 5, 6}, {4, 1, 7, 8}, {5, 7, 2, 9}, {6, 8, 9, 3}};

COROFEM_LANES_INLINE double dot(const double (&x)[4][W], const double (&y)[4][W], int l) {
  return x[0][l] * y[0][l] + x[1][l] * y[1][l] + x[2][l] * y[2][l] + x[3][l] * y[3][l];
}

/// y = M x per lane.
COROFEM_LANES_INLINE void multiply(const Sym4& m, const double (&x)[4][W], double (&y)[4][W]) {
  for (int r = 0; r < 4; ++r)
    for (int l = 0; l < W; ++l)
      y[r][l] = m.m[kOff[r][0]][l] * x[0][l] + m.m[kOff[r][1]][l] * x[1][l] + m.m[kOff[r][2]][l] * x[2][l] +
                m.m[kOff[r][3]][l] * x[3][l];
}

/// N = horn_matrix(S^T) per lane: q^T N q = tr(R(q)^T S^T).
COROFEM_LANES_INLINE void horn_lanes(const double (&s)[9][W], Sym4& n) {
  for (int l = 0; l < W; ++l) {
    const double s00 = s[0][l], s01 = s[1][l], s02 = s[2][l], s10 = s[3][l], s11 = s[4][l], s12 = s[5][l],
                 s20 = s[6][l], s21 = s[7][l], s22 = s[8][l];
    n.m[0][l] = s00 + s11 + s22;
    n.m[1][l] = s00 - s11 - s22;
    n.m[2][l] = -s00 + s11 - s22;
    n.m[3][l] = -s00 - s11 + s22;
    n.m[4][l] = s12 - s21;
    n.m[5][l] = s20 - s02;
    n.m[6][l] = s01 - s10;
    n.m[7][l] = s10 + s01;
    n.m[8][l] = s20 + s02;
    n.m[9][l] = s21 + s12;
  }
}

/// Cholesky factor L (lower, with the inverse of its diagonal) per lane; ok[l] is 0 where a pivot
/// is not positive (that lane's factor is then meaningless), 1 elsewhere.
struct Cholesky4Lanes {
  double l[4][4][W];
  double inverse_diagonal[4][W];
  double ok[W];
};

COROFEM_LANES_INLINE void factor(const Sym4& h, Cholesky4Lanes& f) {
  for (int lane = 0; lane < W; ++lane) f.ok[lane] = 1;
  for (int j = 0; j < 4; ++j) {
    for (int lane = 0; lane < W; ++lane) {
      double d = h.m[kOff[j][j]][lane];
      for (int k = 0; k < j; ++k) d -= f.l[j][k][lane] * f.l[j][k][lane];
      f.ok[lane] = d > 0 ? f.ok[lane] : 0;
      const double ljj = std::sqrt(d > 0 ? d : 1.0);
      f.l[j][j][lane] = ljj;
      f.inverse_diagonal[j][lane] = 1 / ljj;
    }
    for (int i = j + 1; i < 4; ++i)
      for (int lane = 0; lane < W; ++lane) {
        double v = h.m[kOff[i][j]][lane];
        for (int k = 0; k < j; ++k) v -= f.l[i][k][lane] * f.l[j][k][lane];
        f.l[i][j][lane] = v * f.inverse_diagonal[j][lane];
      }
  }
}

/// x = H^-1 b per lane: L y = b, L^T x = y.
COROFEM_LANES_INLINE void solve(const Cholesky4Lanes& f, const double (&b)[4][W], double (&x)[4][W]) {
  double y[4][W];
  for (int i = 0; i < 4; ++i)
    for (int lane = 0; lane < W; ++lane) {
      double v = b[i][lane];
      for (int k = 0; k < i; ++k) v -= f.l[i][k][lane] * y[k][lane];
      y[i][lane] = v * f.inverse_diagonal[i][lane];
    }
  for (int i = 3; i >= 0; --i)
    for (int lane = 0; lane < W; ++lane) {
      double v = y[i][lane];
      for (int k = i + 1; k < 4; ++k) v -= f.l[k][i][lane] * x[k][lane];
      x[i][lane] = v * f.inverse_diagonal[i][lane];
    }
}

/// The Hessian 4a(|q|^2 I + 2 q q^T) - 4N + 2 lambda I per lane (eq. 7).
COROFEM_LANES_INLINE void hessian(const Sym4& n, const double (&q)[4][W], const double (&q2)[W],
                                  const double (&a)[W], const double (&lambda)[W], Sym4& h) {
  for (int r = 0; r < 4; ++r)
    for (int c = r; c < 4; ++c)
      for (int l = 0; l < W; ++l) {
        const double outer = 4 * a[l] * (2 * q[r][l] * q[c][l]) - 4 * n.m[kOff[r][c]][l];
        h.m[kOff[r][c]][l] = r == c ? 4 * a[l] * q2[l] + outer + 2 * lambda[l] : outer;
      }
}

/// Newton on (q, lambda) in every lane, the contract of energy_newton_rotation for its definite
/// case. Lane state is kept as 0/1 numbers and every update is a select, so the lane loops have
/// no branches (they vectorize); a lane that stops keeps its q from then on.
COROFEM_LANES_INLINE void newton_lanes(NewtonLanes& p, double tolerance, int max_iterations) {
  Sym4 n, h;
  Cholesky4Lanes llt;
  double nq[4][W], grad[4][W], hg[4][W], hq[4][W];
  double q2[W], lambda[W], constraint[W], active[W], converged[W], handed_over[W], iterations[W];
  horn_lanes(p.s, n);
  multiply(n, p.q, nq);
  for (int l = 0; l < W; ++l) {
    lambda[l] = 2 * dot(p.q, nq, l) - 2 * p.a[l] * dot(p.q, p.q, l);
    active[l] = 1;
    converged[l] = handed_over[l] = iterations[l] = 0;
  }
  for (int it = 0;; ++it) {
    // Gradient of eq. (5) and constraint of eq. (6); lanes within the tolerance stop.
    if (it > 0) multiply(n, p.q, nq);
    double any = 0;
    for (int l = 0; l < W; ++l) {
      q2[l] = dot(p.q, p.q, l);
      double g2 = 0;
      for (int r = 0; r < 4; ++r) {
        grad[r][l] = 4 * p.a[l] * q2[l] * p.q[r][l] - 4 * nq[r][l] + 2 * lambda[l] * p.q[r][l];
        g2 += grad[r][l] * grad[r][l];
      }
      constraint[l] = q2[l] - 1;
      const bool within = std::sqrt(g2) / (4 * p.a[l]) + std::abs(constraint[l]) < tolerance;
      converged[l] = (active[l] > 0) & within ? 1 : converged[l];  // & and |, not && and ||: no branches
      active[l] = within | (it == max_iterations) ? 0 : active[l];
      any += active[l];
    }
    if (any == 0) break;
    // The bordered Newton step of eqs. (7), (8) by the Schur complement in dl.
    hessian(n, p.q, q2, p.a, lambda, h);
    factor(h, llt);
    solve(llt, grad, hg);
    solve(llt, p.q, hq);
    double dl[W], dq[4][W], check[W];
    for (int l = 0; l < W; ++l) check[l] = dl[l] = (constraint[l] - 2 * dot(p.q, hg, l)) / (4 * dot(p.q, hq, l));
    for (int r = 0; r < 4; ++r)
      for (int l = 0; l < W; ++l) {
        dq[r][l] = -(hg[r][l] + 2 * dl[l] * hq[r][l]);
        check[l] += dq[r][l];  // the sum of the step's entries: not finite if any entry is not
      }
    for (int l = 0; l < W; ++l) {
      const bool step = (active[l] > 0) & (llt.ok[l] > 0) & (check[l] - check[l] == 0);
      // Not the definite case (or no finite step): the scalar routine decides.
      handed_over[l] = (active[l] > 0) & !step ? 1 : handed_over[l];
      for (int r = 0; r < 4; ++r) p.q[r][l] += step ? dq[r][l] : 0.0;
      lambda[l] += step ? dl[l] : 0.0;
      iterations[l] = step ? it + 1 : iterations[l];
      active[l] = step ? 1 : 0;
    }
  }
  // A lane that converged without a step has not shown a definite Hessian yet: a minimizer has
  // one, a saddle does not (energy_rotation.hpp).
  double unchecked = 0;
  for (int l = 0; l < W; ++l) unchecked += (converged[l] > 0) & (iterations[l] == 0) ? 1 : 0;
  if (unchecked > 0) {
    hessian(n, p.q, q2, p.a, lambda, h);  // q2 is the last gradient's, of the final q
    factor(h, llt);
    for (int l = 0; l < W; ++l) converged[l] = (iterations[l] > 0) | (llt.ok[l] > 0) ? converged[l] : 0;
  }
  for (int l = 0; l < W; ++l) {
    p.solved[l] = converged[l] > 0 && handed_over[l] == 0;
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
