#pragma once
// Flexible GMRES (Saad 1993): restarted GMRES right-preconditioned by a preconditioner that may
// change from one application to the next (an inner iterative solve, such as MG-PCG to a
// tolerance), for a matrix that need not be symmetric: static Newton's corotated tangent.
#include <Eigen/Core>
#include <functional>

#include "linalg/linear_solver.hpp"

namespace corofem {

/// z = M^{-1} v, any approximate inverse of A. z arrives sized and zero: an iterative
/// preconditioner may start from it as its initial guess.
using FlexiblePreconditioner = std::function<void(const Eigen::VectorXd& v, Eigen::VectorXd& z)>;

struct FlexibleGmresSettings {
  double tolerance = 1e-10;  ///< relative residual |b - A x| / |b|
  int max_iterations = 200;  ///< Arnoldi steps in all, over the restarts
  int restart = 30;          ///< Krylov basis size before a restart (memory: 2 x restart vectors)
};

/// Iterates from x (the initial guess) until |b - A x| <= tolerance |b| or max_iterations; the
/// residual returned is the true one, |b - A x| / |b|, computed after the last restart. Never
/// throws for non-convergence (the caller may fall back to a direct solve): compare the returned
/// residual with the tolerance. Throws NumericalFault on a non-finite residual.
SolveStats flexible_gmres(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          const FlexiblePreconditioner& precondition,
                          const FlexibleGmresSettings& settings);

}  // namespace corofem
