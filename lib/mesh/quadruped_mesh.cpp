#include "mesh/quadruped_mesh.hpp"

#include <cmath>

#include "mesh/gmsh_api.hpp"
#include "mesh/gmsh_session.hpp"

namespace corofem {
namespace gmsh = gmsh_api;

TetMesh make_quadruped_mesh(double size) {
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("quadruped mesh size must be a positive number");
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

}  // namespace corofem
