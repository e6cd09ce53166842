#pragma once
// Preconditioned conjugate gradients on a BRC matrix, shared by MG-PCG (a V-cycle as the
// preconditioner) and block-Jacobi PCG.
#include <Eigen/Core>
#include <functional>

#include "linalg/linear_solver.hpp"

namespace corofem {

/// z = M^{-1} r for a symmetric positive definite M (z arrives sized, holding the previous z:
/// overwrite it).
using Preconditioner = std::function<void(const Eigen::VectorXd& r, Eigen::VectorXd& z)>;

/// Iterates from x (the initial guess) until |b - A x| <= tolerance |b| or max_iterations.
/// `name` prefixes the NumericalFault thrown on a non-finite residual and the NotConverged thrown
/// at max_iterations above the tolerance. Returns the relative residual and the convergence factor.
/// `initial_residual`, if given, is b - A x for the x given (sized as b), computed by the caller
/// (MG-PCG computes it beside its coarsest factorization): used instead of a product of its own.
/// `events`, if given, hears every iteration's relative residual (EventObserver::iterated).
SolveStats preconditioned_cg(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                             const Preconditioner& precondition, double tolerance,
                             int max_iterations, const char* name,
                             const Eigen::VectorXd* initial_residual = nullptr,
                             EventObserver* events = nullptr);

/// CG with the inverse 3x3 diagonal blocks as preconditioner ("jacobi-pcg"): the baseline a
/// multigrid preconditioner has to beat.
std::unique_ptr<LinearSolver> make_jacobi_pcg_solver(double tolerance, int max_iterations);

}  // namespace corofem
