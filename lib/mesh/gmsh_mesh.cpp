#include "mesh/gmsh_mesh.hpp"

#include <gmsh.h>

#include <fstream>

#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/msh_precheck.hpp"

namespace corofem {
namespace fs = std::filesystem;

namespace {

void check_readable(const fs::path& file) {
  // gmsh's open on a missing file only logs; check first.
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError("mesh file '" + file.string() + "' does not exist");
  if (!fs::is_regular_file(file, ec))
    throw InputError("mesh file '" + file.string() + "' is not a regular file");
  std::ifstream probe(file, std::ios::binary);
  if (!probe) throw InputError("mesh file '" + file.string() + "' cannot be read");
  if (probe.peek() == std::ifstream::traits_type::eof())
    throw InputError("mesh file '" + file.string() + "' is empty");
}

}  // namespace

TetMesh read_volume_mesh(const fs::path& file) {
  check_readable(file);
  precheck_msh(file);
  GmshSession session;
  call_gmsh(file, "open", [&] { gmsh::open(file.string()); });
  return collect_tets(file);
}

TetMesh tetrahedralize_surface(const fs::path& file, double size) {
  check_readable(file);
  precheck_stl(file);
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("mesh size for '" + file.string() + "' must be a positive number");
  GmshSession session;
  call_gmsh(file, "tetrahedralize", [&] {
    gmsh::merge(file.string());
    // A regular tet of edge h has volume h^3 / 8.5: the bounding box bounds the count from above.
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    require_memory_for_tets(8.5 * (x1 - x0) * (y1 - y0) * (z1 - z0) / (size * size * size),
                            "mesh size " + std::to_string(size) + " for '" + file.string() + "'");
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    if (surfaces.empty()) throw InputError("surface file '" + file.string() + "' has no triangles");
    std::vector<int> surface_tags;
    for (const auto& dt : surfaces) surface_tags.push_back(dt.second);
    int loop = gmsh::model::geo::addSurfaceLoop(surface_tags);
    gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::model::mesh::generate(3);
  });
  return collect_tets(file);
}

}  // namespace corofem
