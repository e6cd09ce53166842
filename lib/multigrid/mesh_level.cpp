#include "multigrid/mesh_level.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "multigrid/point_location.hpp"

namespace corofem {

CoarseLevel make_mesh_level(const std::vector<Vec3>& points, const std::vector<char>& fixed,
                            const TetMesh& coarse, const std::string& name, MeshLevelFit* fit_out) {
  if (coarse.tets.empty()) throw InputError("coarse mesh '" + name + "' has no tets");
  const TetLocator locator(coarse.rest, coarse.tets);
  const double edge = mean_edge_length(coarse);
  const auto box = bounding_box(points);
  const double diagonal = (box[1] - box[0]).norm();
  MeshLevelFit fit;
  CoarseLevel level;
  Transfer& t = level.transfer;
  t.fine = static_cast<int>(points.size());
  t.p_start.push_back(0);
  double farthest = 0;
  for (int l = 0; l < t.fine; ++l) {
    if (fixed.empty() || !fixed[l]) {
      const TetLocation where = locator.locate(points[l]);
      ++fit.located;
      if (where.distance > 0) {
        ++fit.outside;
        farthest = std::max(farthest, where.distance);
        if (where.distance > edge) ++fit.far_outside;
      }
      std::array<std::pair<int, double>, 4> entries;
      for (int v = 0; v < 4; ++v) entries[v] = {coarse.tets[where.tet][v], where.weights[v]};
      std::sort(entries.begin(), entries.end());
      for (const auto& [i, weight] : entries)
        if (weight != 0) {  // an exact zero adds no coupling, only fill
          t.p_col.push_back(i);
          t.p_weight.push_back(weight);
          fit.max_abs_weight = std::max(fit.max_abs_weight, std::abs(weight));
        }
    }
    t.p_start.push_back(static_cast<int>(t.p_col.size()));
  }
  fit.max_outside_distance = edge > 0 ? farthest / edge : 0;
  if (fit.located > 0 && 2 * fit.far_outside > fit.located)
    throw InputError("coarse mesh '" + name + "' does not overlap the level above: " +
                     std::to_string(fit.far_outside) + " of " + std::to_string(fit.located) +
                     " points lie outside it, farther than its mean edge length " +
                     std::to_string(edge));
  if (farthest > 0.25 * diagonal)
    throw InputError("coarse mesh '" + name + "' does not cover the level above: a point lies " +
                     std::to_string(farthest) + " outside it (bounding-box diagonal " +
                     std::to_string(diagonal) + ")");
  for (int i : t.keep_supported_coarse_vertices(coarse.num_vertices()))
    level.points.push_back(coarse.rest[i]);
  fit.dropped_vertices = coarse.num_vertices() - t.coarse;
  if (fit_out) *fit_out = fit;
  return level;
}

}  // namespace corofem
