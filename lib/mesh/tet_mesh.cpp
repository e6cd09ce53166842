#include "mesh/tet_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace corofem {

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

std::array<Vec3, 2> bounding_box(const std::vector<Vec3>& points) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

namespace {

std::string element_name(const TetMesh& mesh, int e) {
  return "element " + std::to_string(mesh.element_tags[e]) + " of '" + mesh.source + "'";
}

void remove_unused_vertices(TetMesh& mesh, MeshValidation& report) {
  std::vector<int> new_index(mesh.rest.size(), -1);
  for (const Tet& t : mesh.tets)
    for (int v : t) new_index[v] = 0;
  int next = 0;
  for (auto& idx : new_index)
    if (idx == 0) idx = next++;
  report.unused_removed = static_cast<int>(mesh.rest.size()) - next;
  if (report.unused_removed == 0) return;
  std::vector<Vec3> rest(next);
  std::vector<std::size_t> tags(next);
  for (std::size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] < 0) continue;
    rest[new_index[v]] = mesh.rest[v];
    tags[new_index[v]] = mesh.node_tags[v];
  }
  for (Tet& t : mesh.tets)
    for (int& v : t) v = new_index[v];
  mesh.rest = std::move(rest);
  mesh.node_tags = std::move(tags);
}

}  // namespace

MeshValidation validate_mesh(TetMesh& mesh) {
  MeshValidation report;
  if (mesh.node_tags.size() != mesh.rest.size()) {
    mesh.node_tags.resize(mesh.rest.size());
    for (std::size_t i = 0; i < mesh.rest.size(); ++i) mesh.node_tags[i] = i + 1;
  }
  if (mesh.element_tags.size() != mesh.tets.size()) {
    mesh.element_tags.resize(mesh.tets.size());
    for (std::size_t i = 0; i < mesh.tets.size(); ++i) mesh.element_tags[i] = i + 1;
  }
  if (mesh.tets.empty()) throw InputError("mesh '" + mesh.source + "' contains no tetrahedra");
  for (std::size_t v = 0; v < mesh.rest.size(); ++v) {
    if (!mesh.rest[v].allFinite())
      throw InputError("node " + std::to_string(mesh.node_tags[v]) + " of '" + mesh.source +
                       "' has a non-finite coordinate");
  }
  const int nv = mesh.num_vertices();
  for (int e = 0; e < mesh.num_tets(); ++e) {
    Tet& t = mesh.tets[e];
    for (int v : t)
      if (v < 0 || v >= nv)
        throw InputError(element_name(mesh, e) + " refers to a node that does not exist");
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (t[a] == t[b]) throw InputError(element_name(mesh, e) + " repeats a node");
    const Vec3 &p0 = mesh.rest[t[0]], &p1 = mesh.rest[t[1]], &p2 = mesh.rest[t[2]],
               &p3 = mesh.rest[t[3]];
    double longest = std::max({(p1 - p0).norm(), (p2 - p0).norm(), (p3 - p0).norm(),
                               (p2 - p1).norm(), (p3 - p1).norm(), (p3 - p2).norm()});
    double volume = signed_volume(p0, p1, p2, p3);
    if (!(std::abs(volume) > 1e-8 * longest * longest * longest))
      throw InputError(element_name(mesh, e) + " is degenerate (volume " + std::to_string(volume) +
                       ", longest edge " + std::to_string(longest) + ")");
    if (volume < 0) {
      std::swap(t[2], t[3]);
      ++report.reoriented;
    }
  }
  remove_unused_vertices(mesh, report);
  return report;
}

}  // namespace corofem
