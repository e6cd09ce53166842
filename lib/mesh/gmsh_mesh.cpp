#include "mesh/gmsh_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "mesh/gmsh_api.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/msh_precheck.hpp"

namespace corofem {
namespace gmsh = gmsh_api;
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

namespace {

void check_size(const fs::path& source, double size) {
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("mesh size for '" + source.string() + "' must be a positive number");
}

/// Fills the current model's surfaces with tets of gmsh size `size` (the models' README recipe:
/// the surface triangles stay the boundary) and returns them.
TetMesh fill_surfaces(const fs::path& source, double size) {
  call_gmsh(source, "tetrahedralize", [&] {
    // A regular tet of edge h has volume h^3 / 8.5: the bounding box bounds the count from above.
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    // gmsh's meshing beside a run: the dragon's dynamic MG-PCG run with its gmsh meshing peaked
    // at 3.4 kB per tet (the solver's own need is checked with the scene, scene/memory_estimate).
    const double tets = 8.5 * (x1 - x0) * (y1 - y0) * (z1 - z0) / (size * size * size);
    require_memory(tets, 3.5e3 * tets,
                   "mesh size " + std::to_string(size) + " for '" + source.string() + "'",
                   "3.5 kB per tet: gmsh's meshing beside an MG-PCG run");
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    if (surfaces.empty())
      throw InputError("surface file '" + source.string() + "' has no triangles");
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
  return collect_tets(source);
}

}  // namespace

TetMesh tetrahedralize_surface(const fs::path& file, double size) {
  check_readable(file);
  precheck_stl(file);
  check_size(file, size);
  GmshSession session;
  call_gmsh(file, "read", [&] { gmsh::merge(file.string()); });
  return fill_surfaces(file, size);
}

TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double size, const std::string& name) {
  check_size(name, size);
  GmshSession session;
  call_gmsh(name, "read", [&] {
    const int tag = gmsh::model::addDiscreteEntity(2);
    std::vector<std::size_t> node_tags(surface.points.size());
    std::vector<double> coordinates;
    for (std::size_t v = 0; v < surface.points.size(); ++v) {
      node_tags[v] = v + 1;
      for (int c = 0; c < 3; ++c) coordinates.push_back(surface.points[v][c]);
    }
    gmsh::model::mesh::addNodes(2, tag, node_tags, coordinates);
    std::vector<std::size_t> triangle_nodes;
    for (const auto& t : surface.triangles)
      for (int v : t) triangle_nodes.push_back(static_cast<std::size_t>(v) + 1);
    gmsh::model::mesh::addElementsByType(tag, 2, {}, triangle_nodes);
  });
  return fill_surfaces(name, size);
}

SurfaceMesh read_surface(const fs::path& file) {
  check_readable(file);
  precheck_stl(file);
  GmshSession session;
  SurfaceMesh surface;
  call_gmsh(file, "read", [&] {
    gmsh::merge(file.string());
    std::vector<std::size_t> node_tags;
    std::vector<double> coordinates, parametric;
    gmsh::model::mesh::getNodes(node_tags, coordinates, parametric, 2, -1, true, false);
    std::size_t max_tag = 0;
    for (std::size_t tag : node_tags) max_tag = std::max(max_tag, tag);
    std::vector<int> index(max_tag + 1, -1);
    for (std::size_t i = 0; i < node_tags.size(); ++i) {
      index[node_tags[i]] = surface.num_vertices();
      surface.points.emplace_back(coordinates[3 * i], coordinates[3 * i + 1],
                                  coordinates[3 * i + 2]);
    }
    std::vector<std::size_t> element_tags, triangle_nodes;
    gmsh::model::mesh::getElementsByType(2, element_tags, triangle_nodes);
    for (std::size_t i = 0; i + 2 < triangle_nodes.size(); i += 3)
      surface.triangles.push_back(
          {index[triangle_nodes[i]], index[triangle_nodes[i + 1]], index[triangle_nodes[i + 2]]});
  });
  if (surface.triangles.empty())
    throw InputError("surface file '" + file.string() + "' has no triangles");
  return surface;
}

}  // namespace corofem
