#pragma once
// Everything a solve needs that is built once from a scene: mesh, element data, the BRC pattern
// with its assembly map, mass, loads and supports.
#include <Eigen/Core>
#include <vector>

#include "element/element_rest.hpp"
#include "fem/assembly_map.hpp"
#include "fem/dirichlet.hpp"

namespace corofem {

struct FeProblem {
  TetMesh mesh;
  std::vector<Material> materials;  ///< per element
  std::vector<ElementRest> elements;
  AssemblyMap assembly;
  BrcMatrix stiffness;             ///< pattern; values of the last assembly
  Eigen::VectorXd mass;            ///< lumped, per DOF
  Eigen::VectorXd external_force;  ///< per DOF
  DirichletConditions dirichlet;

  int num_dofs() const { return 3 * mesh.num_vertices(); }
  /// Current vertex positions x + u.
  std::vector<Vec3> positions(const Eigen::VectorXd& displacement) const;
};

/// Precomputes element data and the stiffness pattern; loads and supports start empty.
FeProblem make_fe_problem(TetMesh mesh, std::vector<Material> materials);

}  // namespace corofem
