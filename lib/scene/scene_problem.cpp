#include "scene/scene_problem.hpp"

#include <Eigen/SVD>
#include <algorithm>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "fem/loads.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/coarse_surface_mesh.hpp"
#include "mesh/connected_parts.hpp"
#include "mesh/locality_order.hpp"
#include "mesh/quadruped_mesh.hpp"

namespace corofem {

TetMesh load_scene_mesh(const MeshSpec& spec) {
  switch (spec.kind) {
    case MeshSpec::Kind::File:
      return read_volume_mesh(spec.path);
    case MeshSpec::Kind::Surface:
      return spec.simplify_surface ? tetrahedralize_coarsened_surface(spec.path, spec.size)
                                   : tetrahedralize_surface(spec.path, spec.size);
    case MeshSpec::Kind::Quadruped:
      return make_quadruped_mesh(spec.size);
    case MeshSpec::Kind::Box:
      break;
  }
  return make_box_mesh(spec.box, spec.cells);
}

namespace {

/// Dimension of the affine hull of the points (0 for one point, 1 for collinear, ...).
int affine_rank(const std::vector<Vec3>& points) {
  if (points.size() < 2) return 0;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::MatrixXd centered(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) centered.row(i) = (points[i] - mean).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(centered);
  const auto s = svd.singularValues();
  int rank = 0;
  for (int i = 0; i < 3; ++i) rank += s[i] > 1e-9 * s[0];
  return rank;
}

/// A static analysis needs each piece of the body held against rigid motions: at least 3
/// non-collinear fixed vertices on every connected part (an STL can hold several bodies).
void require_every_part_held(const Scene& scene, const TetMesh& mesh,
                             const std::vector<char>& fixed) {
  const ConnectedParts parts = connected_parts(mesh);
  std::vector<std::vector<Vec3>> fixed_points(parts.count);
  std::vector<int> vertices(parts.count, 0);
  std::vector<Vec3> centre(parts.count, Vec3::Zero());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int part = parts.of_vertex[v];
    ++vertices[part];
    centre[part] += mesh.rest[v];
    if (fixed[v]) fixed_points[part].push_back(mesh.rest[v]);
  }
  for (int part = 0; part < parts.count; ++part) {
    if (affine_rank(fixed_points[part]) >= 2) continue;
    const std::string count = std::to_string(fixed_points[part].size()) + " fixed vertices";
    if (parts.count == 1)
      throw InputError("scene '" + scene.name + "': fixed leaves rigid motions free (" + count +
                       "; a static analysis needs at least 3 non-collinear ones)");
    const Vec3 c = centre[part] / vertices[part];
    throw InputError("scene '" + scene.name + "': fixed leaves rigid motions free on part " +
                     std::to_string(part + 1) + " of the " + std::to_string(parts.count) +
                     " separate parts of the mesh (" + std::to_string(vertices[part]) +
                     " vertices around " + point_text(c) + ", " + count +
                     "); a static analysis needs at least 3 non-collinear ones on every part");
  }
}

}  // namespace

SceneBody build_body(const Scene& scene, MeshValidation* validation) {
  SceneBody body;
  body.mesh = load_scene_mesh(scene.mesh);
  TetMesh& mesh = body.mesh;
  if (scene.mesh.reorder) sort_for_locality(mesh);
  if (validation) *validation = validate_mesh(mesh);  // idempotent; reports what reading changed
  body.materials = materials_per_element(mesh, scene.material, scene.regions);
  const auto& rest = mesh.rest;
  std::vector<char> fixed(mesh.num_vertices(), 0);
  for (std::size_t i = 0; i < scene.fixed.size(); ++i) {
    const auto vertices = vertices_in_box(rest, scene.fixed[i]);
    if (vertices.empty())
      throw InputError("scene '" + scene.name + "': fixed[" + std::to_string(i) +
                       "].box selects no vertex of the mesh");
    for (int v : vertices) fixed[v] = 1;
  }
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (fixed[v]) body.fixed_vertices.push_back(v);
  if (scene.analysis.type == AnalysisType::Static) require_every_part_held(scene, mesh, fixed);
  body.external_force = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  if (scene.gravity.norm() > 0)
    body.external_force += gravity_load(mesh, body.materials, scene.gravity);
  for (std::size_t i = 0; i < scene.forces.size(); ++i) {
    const auto vertices = vertices_in_box(rest, scene.forces[i].box);
    if (vertices.empty())
      throw InputError("scene '" + scene.name + "': forces[" + std::to_string(i) +
                       "].box selects no vertex of the mesh");
    add_spread_force(body.external_force, vertices, scene.forces[i].total);
  }
  return body;
}

FeProblem make_problem(SceneBody body) {
  FeProblem problem = make_fe_problem(std::move(body.mesh), std::move(body.materials));
  for (int v : body.fixed_vertices) problem.dirichlet.fix_vertex(v);
  problem.external_force = std::move(body.external_force);
  return problem;
}

void renumber_supports_and_loads(SceneBody& body, const std::vector<int>& new_index) {
  for (int& v : body.fixed_vertices) v = new_index[v];
  std::sort(body.fixed_vertices.begin(), body.fixed_vertices.end());
  Eigen::VectorXd force(body.external_force.size());
  for (std::size_t v = 0; v < new_index.size(); ++v)
    force.segment<3>(3 * new_index[v]) = body.external_force.segment<3>(3 * v);
  body.external_force = std::move(force);
}

SceneBody body_part(const SceneBody& whole, RankPart& part) {
  SceneBody body;
  body.mesh = std::move(part.mesh);
  part.mesh = {};
  for (int t : part.global_tet) body.materials.push_back(whole.materials[t]);
  body.external_force.resize(3 * body.mesh.num_vertices());
  for (int v = 0; v < body.mesh.num_vertices(); ++v) {
    const int g = part.global_vertex[v];
    body.external_force.segment<3>(3 * v) = whole.external_force.segment<3>(3 * g);
    if (std::binary_search(whole.fixed_vertices.begin(), whole.fixed_vertices.end(), g))
      body.fixed_vertices.push_back(v);
  }
  return body;
}

FeProblem build_problem(const Scene& scene, MeshValidation* validation) {
  return make_problem(build_body(scene, validation));
}

}  // namespace corofem
