#include "fem/fe_problem.hpp"

#include "fem/loads.hpp"

namespace corofem {

std::vector<Vec3> FeProblem::positions(const Eigen::VectorXd& displacement) const {
  std::vector<Vec3> p(mesh.rest.size());
  for (std::size_t v = 0; v < p.size(); ++v) p[v] = mesh.rest[v] + displacement.segment<3>(3 * v);
  return p;
}

FeProblem make_fe_problem(TetMesh mesh, std::vector<Material> materials) {
  FeProblem p;
  p.mesh = std::move(mesh);
  p.materials = std::move(materials);
  p.elements = precompute_elements(p.mesh, p.materials);
  p.stiffness = make_stiffness_pattern(p.mesh, p.assembly);
  p.mass = lumped_mass(p.mesh, p.materials);
  p.external_force = Eigen::VectorXd::Zero(p.num_dofs());
  p.dirichlet = DirichletConditions::none(p.num_dofs());
  return p;
}

}  // namespace corofem
