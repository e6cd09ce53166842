#include "mesh/surface_shells.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/disjoint_sets.hpp"

namespace corofem {

namespace {

/// Whether the ray p + t d (t > 0) crosses the triangle (Moeller and Trumbore 1997).
bool ray_crosses(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return false;  // parallel
  const Vec3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return false;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return false;
  return e2.dot(q) / det > 0;
}

/// Whether p lies inside the closed shell: the parity of a ray's crossings, the majority of three
/// rays in directions no mesh is aligned with (a ray through an edge or vertex may miscount).
bool inside_shell(const Vec3& p, const SurfaceMesh& shell) {
  static const std::array<Vec3, 3> kDirections = {Vec3(0.5377, 0.8117, 0.2280).normalized(),
                                                  Vec3(-0.3291, 0.1964, 0.9236).normalized(),
                                                  Vec3(0.7071, -0.6124, -0.3536).normalized()};
  int votes = 0;
  for (const Vec3& d : kDirections) {
    int crossings = 0;
    for (const auto& t : shell.triangles)
      crossings += ray_crosses(p, d, shell.points[t[0]], shell.points[t[1]], shell.points[t[2]]);
    votes += crossings % 2;
  }
  return votes >= 2;
}

/// The volume one closed shell encloses, its triangles facing either way: each edge-connected
/// piece's triangles turned to agree with the first's (two triangles agree when they run their
/// shared edge in opposite directions), then the divergence theorem's sum, taken positive.
double shell_volume(const SurfaceMesh& shell) {
  const std::vector<int> same = welded_vertices(shell);
  const int n = static_cast<int>(shell.triangles.size());
  auto corner = [&](int t, int k) { return same[shell.triangles[t][k % 3]]; };
  std::map<std::array<int, 2>, std::vector<int>> at_edge;  // undirected edge -> its triangles
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      at_edge[{std::min(corner(t, k), corner(t, k + 1)), std::max(corner(t, k), corner(t, k + 1))}]
          .push_back(t);
  auto runs = [&](int t, int a, int b) {  // whether triangle t runs the edge from a to b
    for (int k = 0; k < 3; ++k)
      if (corner(t, k) == a && corner(t, k + 1) == b) return true;
    return false;
  };
  std::vector<int> sign(n, 0);
  double volume = 0;
  for (int first = 0; first < n; ++first) {
    if (sign[first] != 0) continue;
    sign[first] = 1;
    double piece = 0;
    std::vector<int> todo = {first};
    while (!todo.empty()) {
      const int t = todo.back();
      todo.pop_back();
      piece += sign[t] * signed_triangle_volume(shell, shell.triangles[t]);
      for (int k = 0; k < 3; ++k) {
        const int a = corner(t, k), b = corner(t, k + 1);
        for (int u : at_edge[{std::min(a, b), std::max(a, b)}])
          if (sign[u] == 0) {
            sign[u] = runs(u, a, b) ? -sign[t] : sign[t];
            todo.push_back(u);
          }
      }
    }
    volume += std::abs(piece);
  }
  return volume;
}

}  // namespace

double filled_volume(const std::vector<SurfaceShell>& shells) {
  double volume = 0;
  for (const SurfaceShell& shell : shells)
    volume += (shell.depth % 2 == 0 ? 1 : -1) * shell_volume(shell.surface);
  return volume;
}

std::vector<SurfaceShell> surface_shells(const SurfaceMesh& surface) {
  const std::vector<int> same = welded_vertices(surface);
  DisjointSets joined(surface.num_vertices());  // welded vertices, joined by each triangle's
  for (const auto& t : surface.triangles)
    for (int k = 1; k < 3; ++k) joined.join(same[t[0]], same[t[k]]);
  std::vector<SurfaceShell> shells;
  std::map<int, int> shell_of_root;
  std::vector<std::map<int, int>> local_index;  // per shell: welded vertex -> its own index
  for (const auto& t : surface.triangles) {
    const auto [at, added] = shell_of_root.try_emplace(joined.find(same[t[0]]), shells.size());
    if (added) {
      shells.emplace_back();
      local_index.emplace_back();
    }
    SurfaceShell& shell = shells[at->second];
    std::array<int, 3> local{};
    for (int k = 0; k < 3; ++k) {
      const auto [v, is_new] =
          local_index[at->second].try_emplace(same[t[k]], shell.surface.num_vertices());
      if (is_new) shell.surface.points.push_back(surface.points[same[t[k]]]);
      local[k] = v->second;
    }
    shell.surface.triangles.push_back(local);
  }
  // Nesting: each shell's enclosing shells; the immediate one is the most deeply enclosed.
  const int n = static_cast<int>(shells.size());
  std::vector<std::vector<int>> enclosing(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i != j && inside_shell(shells[i].surface.points[0], shells[j].surface))
        enclosing[i].push_back(j);
  for (int i = 0; i < n; ++i) shells[i].depth = static_cast<int>(enclosing[i].size());
  for (int i = 0; i < n; ++i)
    for (int j : enclosing[i])
      if (shells[i].inside < 0 || shells[j].depth > shells[shells[i].inside].depth)
        shells[i].inside = j;
  return shells;
}

}  // namespace corofem
