#include "rotation/energy_newton_batch.hpp"

#include <cmath>

namespace corofem {
namespace {

constexpr int W = kNewtonLanes;

/// A symmetric 4x4 matrix per lane: its 10 entries (00 11 22 33 01 02 03 12 13 23).
struct Sym4 {
  double m[10][W];
};
constexpr int kD[4] = {0, 1, 2, 3};
constexpr int kOff[4][4] = {{0, 4, 5, 6}, {4, 1, 7, 8}, {5, 7, 2, 9}, {6, 8, 9, 3}};

/// x . y in lane l.
inline double dot(const double (&x)[4][W], const double (&y)[4][W], int l) {
  return x[0][l] * y[0][l] + x[1][l] * y[1][l] + x[2][l] * y[2][l] + x[3][l] * y[3][l];
}

/// y = M x per lane.
void multiply(const Sym4& m, const double (&x)[4][W], double (&y)[4][W]) {
  for (int r = 0; r < 4; ++r)
    for (int l = 0; l < W; ++l)
      y[r][l] = m.m[kOff[r][0]][l] * x[0][l] + m.m[kOff[r][1]][l] * x[1][l] + m.m[kOff[r][2]][l] * x[2][l] +
                m.m[kOff[r][3]][l] * x[3][l];
}

/// Cholesky factor L (lower, with the inverse of its diagonal) per lane; ok[l] false where a
/// pivot is not positive (that lane's factor is then meaningless).
struct Cholesky4Lanes {
  double l[4][4][W];
  double inverse_diagonal[4][W];
  bool ok[W];

  explicit Cholesky4Lanes(const Sym4& h) {
    for (int lane = 0; lane < W; ++lane) ok[lane] = true;
    for (int j = 0; j < 4; ++j) {
      for (int lane = 0; lane < W; ++lane) {
        double d = h.m[kD[j]][lane];
        for (int k = 0; k < j; ++k) d -= l[j][k][lane] * l[j][k][lane];
        ok[lane] = ok[lane] && d > 0;
        const double ljj = std::sqrt(d > 0 ? d : 1.0);
        l[j][j][lane] = ljj;
        inverse_diagonal[j][lane] = 1 / ljj;
      }
      for (int i = j + 1; i < 4; ++i)
        for (int lane = 0; lane < W; ++lane) {
          double v = h.m[kOff[i][j]][lane];
          for (int k = 0; k < j; ++k) v -= l[i][k][lane] * l[j][k][lane];
          l[i][j][lane] = v * inverse_diagonal[j][lane];
        }
    }
  }

  /// x = H^-1 b per lane: L y = b, L^T x = y.
  void solve(const double (&b)[4][W], double (&x)[4][W]) const {
    double y[4][W];
    for (int i = 0; i < 4; ++i)
      for (int lane = 0; lane < W; ++lane) {
        double v = b[i][lane];
        for (int k = 0; k < i; ++k) v -= l[i][k][lane] * y[k][lane];
        y[i][lane] = v * inverse_diagonal[i][lane];
      }
    for (int i = 3; i >= 0; --i)
      for (int lane = 0; lane < W; ++lane) {
        double v = y[i][lane];
        for (int k = i + 1; k < 4; ++k) v -= l[k][i][lane] * x[k][lane];
        x[i][lane] = v * inverse_diagonal[i][lane];
      }
  }
};

/// The Hessian 4a(|q|^2 I + 2 q q^T) - 4N + 2 lambda I per lane (eq. 7).
void hessian(const Sym4& n, const double (&q)[4][W], const double (&q2)[W], const double (&a)[W],
             const double (&lambda)[W], Sym4& h) {
  for (int r = 0; r < 4; ++r)
    for (int c = r; c < 4; ++c)
      for (int l = 0; l < W; ++l) {
        const double outer = 4 * a[l] * (2 * q[r][l] * q[c][l]) - 4 * n.m[kOff[r][c]][l];
        h.m[kOff[r][c]][l] = r == c ? 4 * a[l] * q2[l] + outer + 2 * lambda[l] : outer;
      }
}

}  // namespace

void energy_newton_rotations(const Mat3 (&s)[kNewtonLanes], const double (&a)[kNewtonLanes],
                             const Mat3 (&warm)[kNewtonLanes], double tolerance, int max_iterations,
                             NewtonOutcome (&out)[kNewtonLanes]) {
  Sym4 n, h;
  double q[4][W], nq[4][W], grad[4][W], hg[4][W], hq[4][W];
  double q2[W], lambda[W], constraint[W];
  bool active[W], converged[W], scalar[W];
  int iterations[W];
  for (int l = 0; l < W; ++l) {
    const Eigen::Matrix4d m = horn_matrix(s[l].transpose());
    for (int r = 0; r < 4; ++r)
      for (int c = r; c < 4; ++c) n.m[kOff[r][c]][l] = m(r, c);
    const Eigen::Vector4d start = newton_start(warm[l]);
    for (int r = 0; r < 4; ++r) q[r][l] = start[r];
    active[l] = true;
    converged[l] = scalar[l] = false;
    iterations[l] = 0;
  }
  multiply(n, q, nq);
  for (int l = 0; l < W; ++l) {
    lambda[l] = 2 * dot(q, nq, l) - 2 * a[l] * dot(q, q, l);
  }
  for (int it = 0;; ++it) {
    // Gradient of eq. (5) and constraint of eq. (6); lanes within the tolerance stop.
    if (it > 0) multiply(n, q, nq);
    bool any = false;
    for (int l = 0; l < W; ++l) {
      q2[l] = dot(q, q, l);
      double g2 = 0;
      for (int r = 0; r < 4; ++r) {
        grad[r][l] = 4 * a[l] * q2[l] * q[r][l] - 4 * nq[r][l] + 2 * lambda[l] * q[r][l];
        g2 += grad[r][l] * grad[r][l];
      }
      constraint[l] = q2[l] - 1;
      if (!active[l]) continue;
      if (std::sqrt(g2) / (4 * a[l]) + std::abs(constraint[l]) < tolerance) {
        active[l] = false;
        converged[l] = true;
      } else if (it == max_iterations) {
        active[l] = false;
      }
      any = any || active[l];
    }
    if (!any) break;
    // The bordered Newton step of eqs. (7), (8) by the Schur complement in dl.
    hessian(n, q, q2, a, lambda, h);
    const Cholesky4Lanes llt(h);
    llt.solve(grad, hg);
    llt.solve(q, hq);
    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      const double dl = (constraint[l] - 2 * dot(q, hg, l)) / (4 * dot(q, hq, l));
      double dq[4];
      bool finite = std::isfinite(dl);
      for (int r = 0; r < 4; ++r) {
        dq[r] = -(hg[r][l] + 2 * dl * hq[r][l]);
        finite = finite && std::isfinite(dq[r]);
      }
      if (!llt.ok[l] || !finite) {  // not the definite case: the scalar routine decides
        active[l] = false;
        scalar[l] = true;
        continue;
      }
      for (int r = 0; r < 4; ++r) q[r][l] += dq[r];
      lambda[l] += dl;
      iterations[l] = it + 1;
    }
  }
  // A lane that converged without a step has not shown a definite Hessian yet: a minimizer has
  // one, a saddle does not (energy_rotation.hpp).
  bool unchecked = false;
  for (int l = 0; l < W; ++l) unchecked = unchecked || (converged[l] && iterations[l] == 0);
  if (unchecked) {
    hessian(n, q, q2, a, lambda, h);  // q2 is the last gradient's, of the final q
    const Cholesky4Lanes check(h);
    for (int l = 0; l < W; ++l) converged[l] = converged[l] && (iterations[l] > 0 || check.ok[l]);
  }
  for (int l = 0; l < W; ++l) {
    if (scalar[l] || !converged[l]) {
      out[l] = energy_newton_rotation(s[l], a[l], warm[l], tolerance, max_iterations);
      continue;
    }
    out[l].rotation = newton_rotation({q[0][l], q[1][l], q[2][l], q[3][l]});
    out[l].iterations = iterations[l];
    out[l].fell_back = false;
  }
}

}  // namespace corofem
