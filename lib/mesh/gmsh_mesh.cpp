#include "mesh/gmsh_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "core/memory_usage.hpp"
#include "core/number_text.hpp"
#include "mesh/gmsh_api.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/msh_precheck.hpp"
#include "mesh/surface_shells.hpp"

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

/// The current gmsh model's surface triangles, its duplicate vertices merged as gmsh reads them.
SurfaceMesh model_surface() {
  SurfaceMesh surface;
  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric, 2, -1, true, false);
  std::size_t max_tag = 0;
  for (std::size_t tag : node_tags) max_tag = std::max(max_tag, tag);
  std::vector<int> index(max_tag + 1, -1);
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    index[node_tags[i]] = surface.num_vertices();
    surface.points.emplace_back(coordinates[3 * i], coordinates[3 * i + 1], coordinates[3 * i + 2]);
  }
  std::vector<std::size_t> element_tags, triangle_nodes;
  gmsh::model::mesh::getElementsByType(2, element_tags, triangle_nodes);
  for (std::size_t i = 0; i + 2 < triangle_nodes.size(); i += 3)
    surface.triangles.push_back(
        {index[triangle_nodes[i]], index[triangle_nodes[i + 1]], index[triangle_nodes[i + 2]]});
  return surface;
}

/// gmsh fills only a closed surface without coinciding triangles; given one with holes it fails
/// with "No elements in volume 1" or meshes the space around it, and given coinciding triangles
/// with "Invalid boundary mesh (overlapping facets)". Say what and where instead.
void require_fillable(const SurfaceMesh& surface, const fs::path& source) {
  const SurfaceDefects defects = surface_defects(surface);
  const auto& open = defects.open_edges;
  if (!open.empty())
    throw InputError(
        "surface file '" + source.string() + "' is not closed: " + std::to_string(open.size()) +
        " of its edges border one triangle only (the first from " +
        point_text(surface.points[open[0][0]]) + " to " + point_text(surface.points[open[0][1]]) +
        "); corofem fills a closed surface with tets, so its holes must be closed first");
  const auto& coinciding = defects.coinciding_triangles;
  if (!coinciding.empty()) {
    const auto& t = surface.triangles[coinciding[0]];
    throw InputError("surface file '" + source.string() +
                     "' has triangles that coincide with others (" +
                     std::to_string(coinciding.size()) + " of them; the first at " +
                     point_text(surface.points[t[0]]) + ", " + point_text(surface.points[t[1]]) +
                     ", " + point_text(surface.points[t[2]]) +
                     "): a triangle repeated, or two bodies touching along a face, which must be "
                     "merged into one closed surface");
  }
}

void check_size(const fs::path& source, double size) {
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("mesh size for '" + source.string() + "' must be a positive number");
}

/// A volume to fill, as gmsh's surface loops of the model's surface entities: the outer loop
/// first, then its voids'.
using VolumeLoops = std::vector<std::vector<int>>;

/// Fills the current model's surfaces with tets of gmsh size `size` (the models' README recipe:
/// the surface triangles stay the boundary) and returns them: the `volumes` given, or one volume
/// bounded by all the surfaces. `shells` are the surfaces' shells (surface_shells), fillable
/// (require_fillable).
TetMesh fill_surfaces(const fs::path& source, double size, const std::vector<SurfaceShell>& shells,
                      std::vector<VolumeLoops> volumes = {}) {
  call_gmsh(source, "tetrahedralize", [&] {
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    if (surfaces.empty())
      throw InputError("surface file '" + source.string() + "' has no triangles");
    const double tets = expected_tets(shells, size);
    // gmsh's meshing beside a run: the dragon's dynamic MG-PCG run with its gmsh meshing peaked
    // at 3.4 kB per tet (the solver's own need is checked with the scene, scene/memory_estimate).
    require_memory(tets, 3.5e3 * tets,
                   "mesh size " + std::to_string(size) + " for '" + source.string() + "'",
                   "3.5 kB per tet: gmsh's meshing beside an MG-PCG run");
    if (volumes.empty()) {
      std::vector<int> surface_tags;
      for (const auto& dt : surfaces) surface_tags.push_back(dt.second);
      volumes.push_back({surface_tags});
    }
    for (const VolumeLoops& volume : volumes) {
      std::vector<int> loops;
      for (const std::vector<int>& loop : volume)
        loops.push_back(gmsh::model::geo::addSurfaceLoop(loop));
      gmsh::model::geo::addVolume(loops);
    }
    gmsh::model::geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);
    try {
      gmsh::model::mesh::generate(3);
    } catch (const std::exception& e) {
      // gmsh's Delaunay says "PLC Error" of an input whose facets cross.
      if (std::string(e.what()).find("PLC Error") == std::string::npos) throw;
      throw InputError("gmsh could not tetrahedralize '" + source.string() + "': " + e.what() +
                       " (the surface intersects itself, or two of its bodies overlap)");
    }
  });
  return collect_tets(source);
}

/// The surface's shells (surface_shells); a single one keeps the surface's own vertex order.
std::vector<SurfaceShell> shells_of(const SurfaceMesh& surface) {
  std::vector<SurfaceShell> shells = surface_shells(surface);
  if (shells.size() == 1) shells[0].surface = surface;
  return shells;
}

/// Fills the shells with tets: one discrete surface a shell; a body is a shell of even depth with
/// the voids just inside it.
TetMesh fill_shells(const std::vector<SurfaceShell>& shells, double size, const std::string& name) {
  GmshSession session;
  std::vector<VolumeLoops> volumes;
  call_gmsh(name, "read", [&] {
    std::vector<int> tags;
    std::size_t first_node = 1;
    for (const SurfaceShell& shell : shells) {
      const SurfaceMesh& piece = shell.surface;
      tags.push_back(gmsh::model::addDiscreteEntity(2));
      std::vector<std::size_t> node_tags(piece.points.size());
      std::vector<double> coordinates;
      for (std::size_t v = 0; v < piece.points.size(); ++v) {
        node_tags[v] = first_node + v;
        for (int c = 0; c < 3; ++c) coordinates.push_back(piece.points[v][c]);
      }
      gmsh::model::mesh::addNodes(2, tags.back(), node_tags, coordinates);
      std::vector<std::size_t> triangle_nodes;
      for (const auto& t : piece.triangles)
        for (int v : t) triangle_nodes.push_back(first_node + static_cast<std::size_t>(v));
      gmsh::model::mesh::addElementsByType(tags.back(), 2, {}, triangle_nodes);
      first_node += piece.points.size();
    }
    for (std::size_t body = 0; body < shells.size(); ++body) {
      if (shells[body].depth % 2 != 0) continue;
      volumes.push_back({{tags[body]}});
      for (std::size_t v = 0; v < shells.size(); ++v)
        if (shells[v].inside == static_cast<int>(body)) volumes.back().push_back({tags[v]});
    }
  });
  return fill_surfaces(name, size, shells, std::move(volumes));
}

}  // namespace

// gmsh's tets average about h^3 / 5 of volume (3.9-5.2 tets per h^3 on the bunny, horse and
// dragon at the table sizes and finer; 6 is taken, to err high), plus one per surface triangle,
// which gmsh keeps. The volume, not the bounding box: the horse fills 11% of its box, and the
// box's bound refused sizes the machine could run.
double expected_tets(const std::vector<SurfaceShell>& shells, double size) {
  std::size_t triangles = 0;
  for (const SurfaceShell& shell : shells) triangles += shell.surface.triangles.size();
  return 6 * filled_volume(shells) / (size * size * size) + static_cast<double>(triangles);
}

TetMesh tetrahedralize_surface(const fs::path& file, double size) {
  check_readable(file);
  precheck_stl(file);
  check_size(file, size);
  std::vector<SurfaceShell> shells;
  {
    GmshSession session;
    gmsh::vectorpair entities;
    call_gmsh(file, "read", [&] {
      gmsh::merge(file.string());
      gmsh::model::getEntities(entities, 2);
      const SurfaceMesh surface = model_surface();
      require_fillable(surface, file);
      shells = shells_of(surface);
    });
    if (entities.size() <= 1 && shells.size() <= 1) return fill_surfaces(file, size, shells);
  }
  // Several solids, or several shells: filled shell by shell. As gmsh read them, two bodies in
  // two solids gave "No elements in volume 1", and a void was filled.
  return fill_shells(shells, size, file.string());
}

TetMesh tetrahedralize_surface(const SurfaceMesh& surface, double size, const std::string& name) {
  check_size(name, size);
  require_fillable(surface, name);
  return fill_shells(shells_of(surface), size, name);
}

SurfaceMesh read_surface(const fs::path& file) {
  check_readable(file);
  precheck_stl(file);
  GmshSession session;
  SurfaceMesh surface;
  call_gmsh(file, "read", [&] {
    gmsh::merge(file.string());
    surface = model_surface();
  });
  if (surface.triangles.empty())
    throw InputError("surface file '" + file.string() + "' has no triangles");
  require_fillable(surface, file);
  return surface;
}

}  // namespace corofem
