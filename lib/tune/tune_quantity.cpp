#include "tune/tune_quantity.hpp"

#include "multigrid/point_location.hpp"

namespace corofem {
namespace {

Vec3 vertex_displacement(const FinalState& s, int v) {
  return s.displacement.segment<3>(3 * static_cast<Eigen::Index>(v));
}

/// The state's displacement interpolated at `p` (extrapolated from the nearest tet outside).
Vec3 displacement_at(const FinalState& s, const TetLocator& locator, const Vec3& p) {
  const TetLocation at = locator.locate(p);
  Vec3 u = Vec3::Zero();
  for (int k = 0; k < 4; ++k) u += at.weights[k] * vertex_displacement(s, s.mesh.tets[at.tet][k]);
  return u;
}

double relative(double difference, double norm) {
  return norm > 0 ? difference / norm : difference;
}

/// Mean of the state's displacement over `points` (interpolated at each).
Vec3 mean_at(const FinalState& s, const std::vector<Vec3>& points) {
  const TetLocator locator(s.mesh.rest, s.mesh.tets);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += displacement_at(s, locator, p);
  return points.empty() ? sum : Vec3(sum / static_cast<double>(points.size()));
}

}  // namespace

double quantity_error(const QuantitySpec& quantity, const FinalState& candidate,
                      const FinalState& reference) {
  switch (quantity.kind) {
    case TuneQuantity::Displacement: {
      const bool same_mesh =
          candidate.mesh.rest == reference.mesh.rest && candidate.mesh.tets == reference.mesh.tets;
      if (same_mesh)
        return relative((candidate.displacement - reference.displacement).norm(),
                        reference.displacement.norm());
      const TetLocator locator(reference.mesh.rest, reference.mesh.tets);
      double difference = 0, norm = 0;
      for (int v = 0; v < candidate.mesh.num_vertices(); ++v) {
        const Vec3 u_ref = displacement_at(reference, locator, candidate.mesh.rest[v]);
        difference += (vertex_displacement(candidate, v) - u_ref).squaredNorm();
        norm += u_ref.squaredNorm();
      }
      return relative(std::sqrt(difference), std::sqrt(norm));
    }
    case TuneQuantity::Tip: {
      const Vec3 u_ref = displacement_at(
          reference, TetLocator(reference.mesh.rest, reference.mesh.tets), quantity.tip);
      const Vec3 u = displacement_at(
          candidate, TetLocator(candidate.mesh.rest, candidate.mesh.tets), quantity.tip);
      return relative((u - u_ref).norm(), u_ref.norm());
    }
    case TuneQuantity::Probe: {
      // At the reference's vertices in the box, so that every run is sampled at the same points.
      std::vector<Vec3> points;
      for (int v : vertices_in_box(reference.mesh.rest, quantity.probe))
        points.push_back(reference.mesh.rest[v]);
      const Vec3 m_ref = mean_at(reference, points);
      return relative((mean_at(candidate, points) - m_ref).norm(), m_ref.norm());
    }
  }
  return 0;
}

Vec3 tip_point(const FinalState& reference, const std::vector<AxisBox>& fixed) {
  const std::vector<Vec3>& rest = reference.mesh.rest;
  int best = 0;
  if (fixed.empty()) {
    for (int v = 1; v < reference.mesh.num_vertices(); ++v)
      if (vertex_displacement(reference, v).norm() > vertex_displacement(reference, best).norm())
        best = v;
    return rest[best];
  }
  Vec3 support = Vec3::Zero();
  for (const AxisBox& box : fixed) support += 0.5 * (box.lo + box.hi);
  support /= static_cast<double>(fixed.size());
  for (int v = 1; v < reference.mesh.num_vertices(); ++v)
    if ((rest[v] - support).norm() > (rest[best] - support).norm()) best = v;
  return rest[best];
}

}  // namespace corofem
