#include "mesh/quadruped_mesh.hpp"

#include <cmath>
#include <deque>
#include <mutex>
#include <utility>

#include "mesh/gmsh_api.hpp"
#include "mesh/gmsh_session.hpp"

namespace corofem {
namespace gmsh = gmsh_api;

namespace {

/// The sizes a process keeps meshed: a report's (three Table 1 sizes, their coarse levels, the
/// stability study's and the sweeps') with room to spare; 67k tets are about 2 MB.
constexpr std::size_t kKeptMeshes = 24;

TetMesh mesh_with_gmsh(double size) {
  const char* source = "quadruped";
  GmshSession session;
  call_gmsh(source, "build", [&] {
    namespace occ = gmsh::model::occ;
    gmsh::model::add(source);
    const int body = occ::addBox(0, -0.25, 1.0, 1.6, 0.5, 0.5);
    gmsh::vectorpair tools;
    for (double x : {0.15, 1.45})
      for (double y : {-0.15, 0.15})
        tools.push_back({3, occ::addCylinder(x, y, 0, 0, 0, 1.05, 0.08)});
    tools.push_back({3, occ::addCylinder(1.45, 0, 1.35, 0.45, 0, 0.6, 0.13)});
    tools.push_back({3, occ::addBox(1.8, -0.1, 1.85, 0.45, 0.2, 0.23)});
    gmsh::vectorpair fused;
    std::vector<gmsh::vectorpair> map;
    occ::fuse({{3, body}}, tools, fused, map);
    occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * size);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::model::mesh::generate(3);
  });
  return collect_tets(source);
}

}  // namespace

TetMesh make_quadruped_mesh(double size) {
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("quadruped mesh size must be a positive number");
  // gmsh gives a size the same tets every time, and a report builds each scene many times (Table
  // 1's quadruped-67k nine times, about 3 s of gmsh each, and its coarse levels with it): a process
  // meshes each size once. Under one lock: gmsh runs one session at a time anyway.
  static std::mutex lock;
  static std::deque<std::pair<double, TetMesh>> kept;
  const std::lock_guard<std::mutex> hold(lock);
  for (const auto& [kept_size, mesh] : kept)
    if (kept_size == size) return mesh;
  TetMesh mesh = mesh_with_gmsh(size);
  kept.emplace_back(size, mesh);
  if (kept.size() > kKeptMeshes) kept.pop_front();
  return mesh;
}

}  // namespace corofem
