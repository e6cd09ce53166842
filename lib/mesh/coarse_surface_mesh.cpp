#include "mesh/coarse_surface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/surface_simplification.hpp"

namespace corofem {

namespace {

int target_vertices(const SurfaceMesh& fine, double size) {
  const double per_vertex = std::sqrt(3.0) / 2 * size * size;  // two triangles of edge `size`
  return std::max(8, static_cast<int>(std::lround(surface_area(fine) / per_vertex)));
}

}  // namespace

int coarsened_surface_vertices(const SurfaceMesh& fine, double size) {
  return std::min(fine.num_vertices(), target_vertices(fine, size));
}

TetMesh tetrahedralize_coarsened_surface(const std::filesystem::path& file, double size) {
  return tetrahedralize_coarsened_surface(read_surface(file), file, size);
}

TetMesh tetrahedralize_coarsened_surface(const SurfaceMesh& fine, const std::filesystem::path& file,
                                         double size) {
  const int target = target_vertices(fine, size);
  const SurfaceMesh coarse = target < fine.num_vertices() ? simplify_surface(fine, target) : fine;
  const std::vector<Vec3> moves = covering_moves(coarse, fine);
  const std::string name = file.string() + " (surface coarsened from " +
                           std::to_string(fine.num_vertices()) + " to " +
                           std::to_string(coarse.num_vertices()) + " vertices";
  // Grown outward to cover the body, by less where the grown surface would intersect itself
  // (gmsh refuses it: thin parts side by side, as the dragon's, which takes a quarter), at worst
  // not at all.
  for (const double fraction : {1.0, 0.5, 0.25, 0.0}) {
    SurfaceMesh grown = coarse;
    for (std::size_t v = 0; v < moves.size(); ++v) grown.points[v] += fraction * moves[v];
    const std::string source = name + ", grown outward " + general_number(fraction) + "x)";
    try {
      TetMesh mesh = tetrahedralize_surface(grown, size, source);
      mesh.source = source;
      return mesh;
    } catch (const InputError&) {
      if (fraction == 0.0) throw;
    }
  }
  throw std::logic_error("tetrahedralize_coarsened_surface: unreachable");
}

}  // namespace corofem
