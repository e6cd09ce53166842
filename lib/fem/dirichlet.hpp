#pragma once
// Prescribed DOF values imposed symmetrically: known columns move to the right-hand side, the
// rows and columns of fixed DOFs become identity, so A stays symmetric positive definite.
#include <Eigen/Core>
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

struct DirichletConditions {
  std::vector<char> fixed;  ///< per DOF: 1 if prescribed
  Eigen::VectorXd value;    ///< prescribed value where fixed (ignored elsewhere)

  static DirichletConditions none(int num_dofs);
  void fix_vertex(int v, const Eigen::Vector3d& displacement = Eigen::Vector3d::Zero());
  int num_fixed() const;
  /// Per vertex: 1 if any of its DOFs is prescribed (its row and column of A change).
  std::vector<char> supported_vertices() const;
  bool any() const { return num_fixed() > 0; }
};

/// Applies the conditions to A x = b in place.
void apply_dirichlet(const DirichletConditions& bc, BrcMatrix& a, Eigen::VectorXd& b);
/// A's part of apply_dirichlet alone: the fixed DOFs' rows and columns become identity, for a
/// right-hand side that carries the prescribed values' lift already.
void apply_dirichlet_to_matrix(const DirichletConditions& bc, BrcMatrix& a);

/// Euclidean norm of v over the free DOFs only.
double free_norm(const DirichletConditions& bc, const Eigen::VectorXd& v);

}  // namespace corofem
