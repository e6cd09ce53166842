#include "mesh/coarse_surface_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/gmsh_mesh.hpp"
#include "mesh/surface_simplification.hpp"

namespace corofem {

TetMesh tetrahedralize_coarsened_surface(const std::filesystem::path& file, double size) {
  const SurfaceMesh fine = read_surface(file);
  const double per_vertex = std::sqrt(3.0) / 2 * size * size;  // two triangles of edge `size`
  const int target =
      std::max(8, static_cast<int>(std::lround(surface_area(fine) / per_vertex)));
  const SurfaceMesh coarse =
      target < fine.num_vertices() ? simplify_surface(fine, target) : fine;
  const std::string name = file.string() + " (surface coarsened from " +
                           std::to_string(fine.num_vertices()) + " to " +
                           std::to_string(coarse.num_vertices()) + " vertices)";
  TetMesh mesh = tetrahedralize_surface(coarse, size, name);
  mesh.source = name;
  return mesh;
}

}  // namespace corofem
