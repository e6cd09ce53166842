#pragma once
// Corotated assembly (paper section 2): Ktilde_e = Q_e K_e Q_e^T written into the BRC matrix
// through the stored block indices, and in the same pass the elastic force Ktilde_e p_e - f0_e
// (f0_e = Q_e K_e x_e). Q_e = I gives the small-strain system.
#include <Eigen/Core>
#include <vector>

#include "element/element_rest.hpp"
#include "fem/assembly_map.hpp"
#include "fem/fe_problem.hpp"

namespace corofem {

/// Overwrites K's values with sum_e Q_e K_e Q_e^T and `force` with the elastic internal force at
/// `displacement` (as internal_forces() defines it, from the gradients the blocks are built from:
/// the step's right-hand side needs no pass of its own), each thread of map.rows writing its own
/// rows (bit-identical at every thread count).
/// `rotations` holds Qhat_e per element (the rotation taking the rest element to the deformed one).
/// `matrix_scale`: K gets matrix_scale sum_e Q_e K_e Q_e^T, plus `diagonal` (one entry per DOF)
/// on the diagonal when given: a time step's matrix (dt beta + dt^2) Ktilde + (1 + dt alpha) M,
/// written in this pass (no pass to scale a copy, none to add the mass into the diagonal blocks
/// spread over the matrix). The force is neither.
void assemble_corotated(const std::vector<ElementRest>& elements, const TetMesh& mesh,
                        const AssemblyMap& map, const std::vector<Mat3>& rotations,
                        const Eigen::VectorXd& displacement, BrcMatrix& k, Eigen::VectorXd& force,
                        double matrix_scale = 1.0, const Eigen::VectorXd* diagonal = nullptr);

/// Elastic internal force, element by element: f_int = sum_e Q_e K_e (Q_e^T p_e - x_e), p = x + u.
/// Equals Ktilde p - f0 of the assembled system, but is evaluated from vertex-0 offsets as
/// (Q^T - I)(x_b - x_0) + Q^T (u_b - u_0) (K_e annihilates the dropped translation), so it keeps
/// full relative accuracy where Ktilde p - f0 cancels terms of size |K||x| >> |f|.
/// Zero for any rigid motion of the rest mesh.
/// Threaded as assemble_corotated, over problem.assembly.rows.
Eigen::VectorXd internal_forces(const FeProblem& problem, const std::vector<Mat3>& rotations,
                                const Eigen::VectorXd& displacement);

/// Corotated elastic energy sum_e 1/2 s_e^T K_e s_e, s_e = Q_e^T p_e - x_e (from vertex-0 offsets,
/// as internal_forces). With Q = polar(F) it is the potential of internal_forces; with other
/// rotations it is the same expression, but no longer a potential (the force is not its gradient).
double elastic_energy(const std::vector<ElementRest>& elements, const TetMesh& mesh,
                      const std::vector<Mat3>& rotations, const Eigen::VectorXd& displacement);

}  // namespace corofem
