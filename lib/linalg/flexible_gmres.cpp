#include "linalg/flexible_gmres.hpp"

#include <cmath>
#include <vector>

#include "core/errors.hpp"

namespace corofem {

SolveStats flexible_gmres(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          const FlexiblePreconditioner& precondition,
                          const FlexibleGmresSettings& settings) {
  SolveStats stats;
  const double b_norm = start_iterative_solve(b, x);
  if (b_norm == 0) return stats;
  const int m = settings.restart;
  const double target = settings.tolerance * b_norm;
  std::vector<Eigen::VectorXd> v(m + 1), z(m);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m + 1, m);  // the Hessenberg matrix, then R
  Eigen::VectorXd cs(m), sn(m), g(m + 1), w, r;
  a.residual(b, x, r);
  double beta = r.norm();
  const double r0 = beta;
  while (beta > target && stats.iterations < settings.max_iterations) {
    v[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int k = 0;  // basis vectors built in this cycle
    double estimate = beta;
    while (k < m && stats.iterations < settings.max_iterations && estimate > target) {
      z[k].setZero(b.size());  // the preconditioner's contract: z arrives zero
      precondition(v[k], z[k]);
      a.multiply(z[k], w);
      for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
        h(i, k) = v[i].dot(w);
        w -= h(i, k) * v[i];
      }
      const double next = w.norm();
      if (!std::isfinite(next))
        throw NumericalFault("GMRES: a non-finite Krylov vector (the preconditioner or matrix)");
      h(k + 1, k) = next;
      if (next > 0) v[k + 1] = w / next;
      for (int i = 0; i < k; ++i) {  // the earlier rotations on the new column
        const double t = cs[i] * h(i, k) + sn[i] * h(i + 1, k);
        h(i + 1, k) = -sn[i] * h(i, k) + cs[i] * h(i + 1, k);
        h(i, k) = t;
      }
      const double d = std::hypot(h(k, k), h(k + 1, k));  // the rotation zeroing h(k + 1, k)
      if (d == 0) break;  // A z = 0: the column adds nothing (a singular A or preconditioner)
      cs[k] = h(k, k) / d;
      sn[k] = h(k + 1, k) / d;
      h(k, k) = d;
      h(k + 1, k) = 0;
      g[k + 1] = -sn[k] * g[k];
      g[k] *= cs[k];
      estimate = std::abs(g[k + 1]);
      ++k;
      ++stats.iterations;
      if (next == 0) break;  // the space is invariant: x is exact in it
    }
    // x += Z y, R y = g (the rotated Hessenberg matrix is upper triangular).
    const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    for (int i = 0; i < k; ++i) x += y[i] * z[i];
    a.residual(b, x, r);
    const double previous = beta;
    beta = r.norm();
    if (!std::isfinite(beta)) throw NumericalFault("GMRES: the residual became non-finite");
    if (beta >= previous) break;  // no progress in a whole cycle: a restart would repeat it
  }
  stats.residual = beta / b_norm;
  stats.convergence_factor =
      stats.iterations > 0 && r0 > 0 ? std::pow(beta / r0, 1.0 / stats.iterations) : 0;
  return stats;
}

}  // namespace corofem
