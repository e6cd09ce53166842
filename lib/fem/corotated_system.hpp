#pragma once
// One linearization of the corotated problem at the current positions: rotate, assemble, and the
// checks every step needs (non-finite state, inverted elements).
#include "fem/fe_problem.hpp"
#include "fem/simulation_result.hpp"
#include "rotation/rotation_extractor.hpp"

namespace corofem {

/// Where linearize() assembles scale Ktilde + diag(diagonal): into `matrix` (with
/// problem.stiffness's pattern; a time step's), or, by default, Ktilde into problem.stiffness.
struct AssemblyTarget {
  BrcMatrix* matrix = nullptr;
  double scale = 1.0;
  const Eigen::VectorXd* diagonal = nullptr;  ///< per DOF; none: nothing added
};

/// Extracts rotations at `positions` = x + `displacement` (warm-started from `rotations`) and
/// assembles into `target` and the elastic force there into `force` (internal_forces' f_int).
/// Phases "rotate" and "assemble" are timed on `clock`.
void linearize(FeProblem& problem, RotationExtractor& extractor, const std::vector<Vec3>& positions,
               const Eigen::VectorXd& displacement, std::vector<Mat3>& rotations,
               Eigen::VectorXd& force, PhaseClock& clock, const AssemblyTarget& target = {});

/// Number of elements with det F <= 0 at `positions`; with `only`, of the tets it flags.
int count_inverted(const FeProblem& problem, const std::vector<Vec3>& positions,
                   const std::vector<char>* only = nullptr);

/// Throws NumericalFault naming `what` (displacement, force, ...), `where` (the step) and the
/// first element touching a non-finite DOF of v, or, where v's entries are finite but its norm
/// overflows, its largest entry.
void check_finite(const FeProblem& problem, const Eigen::VectorXd& v, const std::string& what,
                  const std::string& where);

}  // namespace corofem
