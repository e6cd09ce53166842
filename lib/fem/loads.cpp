#include "fem/loads.hpp"

namespace corofem {

Eigen::VectorXd lumped_mass(const TetMesh& mesh, const std::vector<Material>& materials) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const Tet& t = mesh.tets[e];
    const double quarter =
        0.25 * materials[e].density *
        signed_volume(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]], mesh.rest[t[3]]);
    for (int v : t) m.segment<3>(3 * v).array() += quarter;
  }
  return m;
}

Eigen::VectorXd gravity_load(const TetMesh& mesh, const std::vector<Material>& materials,
                             const Vec3& gravity) {
  Eigen::VectorXd m = lumped_mass(mesh, materials);
  Eigen::VectorXd f(m.size());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    f.segment<3>(3 * v) = m.segment<3>(3 * v).cwiseProduct(gravity);
  return f;
}

void add_spread_force(Eigen::VectorXd& f, const std::vector<int>& vertices, const Vec3& total,
                      int among) {
  if (vertices.empty()) return;
  const Vec3 share = total / static_cast<double>(among > 0 ? among : vertices.size());
  for (int v : vertices) f.segment<3>(3 * v) += share;
}

}  // namespace corofem
