#include "multigrid/point_location.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace corofem {
namespace {

/// Closest point to p on triangle (a, b, c): Ericson, Real-Time Collision Detection, 5.1.5.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

constexpr double kInside = -1e-12;  // a coordinate this far below 0 is round-off on a face

}  // namespace

TetLocator::TetLocator(const std::vector<Vec3>& vertices, const std::vector<Tet>& tets)
    : vertices_(vertices), tets_(tets), inverse_edges_(tets.size()) {
  const auto box = bounding_box(vertices);
  double mean_extent = 0;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const Vec3& a = vertices[tets[t][0]];
    Eigen::Matrix3d edges;
    edges << vertices[tets[t][1]] - a, vertices[tets[t][2]] - a, vertices[tets[t][3]] - a;
    inverse_edges_[t] = edges.inverse();
    mean_extent += (edges.cwiseAbs().rowwise().maxCoeff()).maxCoeff();
  }
  // Buckets about one tet across: a handful of tets per bucket.
  cell_ = tets.empty() ? 1 : std::max(mean_extent / tets.size(), 1e-300);
  origin_ = box[0];
  const Vec3 span = box[1] - box[0];
  for (int d = 0; d < 3; ++d)
    dims_[d] = std::clamp(static_cast<int>(std::ceil(span[d] / cell_)), 1, 1024);
  const double cells = static_cast<double>(dims_[0]) * dims_[1] * dims_[2];
  if (cells > 8.0 * tets.size() + 64) cell_ *= std::cbrt(cells / (8.0 * tets.size() + 64));
  for (int d = 0; d < 3; ++d)
    dims_[d] = std::clamp(static_cast<int>(std::ceil(span[d] / cell_)), 1, 1024);
  // Two passes: count, then fill (counting sort by bucket).
  const int buckets = dims_[0] * dims_[1] * dims_[2];
  bucket_start_.assign(buckets + 1, 0);
  auto for_each_bucket = [&](int t, auto&& visit) {
    Vec3 lo = vertices[tets[t][0]], hi = lo;
    for (int v = 1; v < 4; ++v) {
      lo = lo.cwiseMin(vertices[tets[t][v]]);
      hi = hi.cwiseMax(vertices[tets[t][v]]);
    }
    const auto c0 = cell_of(lo), c1 = cell_of(hi);
    for (int k = c0[2]; k <= c1[2]; ++k)
      for (int j = c0[1]; j <= c1[1]; ++j)
        for (int i = c0[0]; i <= c1[0]; ++i) visit(bucket_of({i, j, k}));
  };
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for_each_bucket(t, [&](int b) { ++bucket_start_[b + 1]; });
  for (int b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  bucket_tets_.resize(bucket_start_[buckets]);
  std::vector<int> next(bucket_start_.begin(), bucket_start_.end() - 1);
  for (int t = 0; t < static_cast<int>(tets.size()); ++t)
    for_each_bucket(t, [&](int b) { bucket_tets_[next[b]++] = t; });
}

std::array<int, 3> TetLocator::cell_of(const Vec3& p) const {
  std::array<int, 3> c;
  for (int d = 0; d < 3; ++d) {
    const double x = std::floor((p[d] - origin_[d]) / cell_);
    c[d] = static_cast<int>(std::clamp(x, 0.0, static_cast<double>(dims_[d] - 1)));
  }
  return c;
}

int TetLocator::bucket_of(const std::array<int, 3>& c) const {
  return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]);
}

std::array<double, 4> TetLocator::barycentric(int t, const Vec3& p) const {
  const Vec3 l = inverse_edges_[t] * (p - vertices_[tets_[t][0]]);
  return {1 - l.sum(), l[0], l[1], l[2]};
}

double TetLocator::distance_to_tet(int t, const Vec3& p) const {
  const auto w = barycentric(t, p);
  if (*std::min_element(w.begin(), w.end()) >= 0) return 0;
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double best = std::numeric_limits<double>::infinity();
  const Tet& tet = tets_[t];
  for (const auto& f : kFaces)
    best = std::min(best, (p - closest_on_triangle(p, vertices_[tet[f[0]]], vertices_[tet[f[1]]],
                                                   vertices_[tet[f[2]]]))
                              .norm());
  return best;
}

TetLocation TetLocator::locate(const Vec3& p) const {
  TetLocation found;
  // Inside: the candidate tets of p's bucket; the best-inside one wins (deterministic on faces).
  const auto cell = cell_of(p);
  const int b = bucket_of(cell);
  double best_min = -std::numeric_limits<double>::infinity();
  for (int k = bucket_start_[b]; k < bucket_start_[b + 1]; ++k) {
    const int t = bucket_tets_[k];
    const auto w = barycentric(t, p);
    const double smallest = *std::min_element(w.begin(), w.end());
    if (smallest > best_min) {
      best_min = smallest;
      found.tet = t;
      found.weights = w;
    }
  }
  if (found.tet >= 0 && best_min >= kInside) {
    // Round-off on a face or at a vertex: drop it rather than add fill to R.
    double sum = 0;
    for (double& w : found.weights) sum += (w = w < 1e-14 ? 0.0 : w);
    for (double& w : found.weights) w /= sum;
    return found;
  }
  // Outside: rings of buckets around p's (clamped) bucket until no closer tet can exist. A
  // bucket in ring r lies at least (r - 1) cells from the clamped cell, and the clamped point is
  // no farther from any point of the grid than p itself.
  found = {};
  found.distance = std::numeric_limits<double>::infinity();
  const int max_ring = *std::max_element(dims_.begin(), dims_.end());
  for (int r = 0; r <= max_ring; ++r) {
    if ((r - 1) * cell_ > found.distance) break;
    for (int k = cell[2] - r; k <= cell[2] + r; ++k)
      for (int j = cell[1] - r; j <= cell[1] + r; ++j)
        for (int i = cell[0] - r; i <= cell[0] + r; ++i) {
          if (std::max({std::abs(i - cell[0]), std::abs(j - cell[1]), std::abs(k - cell[2])}) != r)
            continue;
          if (i < 0 || j < 0 || k < 0 || i >= dims_[0] || j >= dims_[1] || k >= dims_[2]) continue;
          const int bucket = bucket_of({i, j, k});
          for (int m = bucket_start_[bucket]; m < bucket_start_[bucket + 1]; ++m) {
            const int t = bucket_tets_[m];
            const double d = distance_to_tet(t, p);
            if (d < found.distance || (d == found.distance && t < found.tet)) {
              found.distance = d;
              found.tet = t;
            }
          }
        }
  }
  if (found.tet >= 0) found.weights = barycentric(found.tet, p);
  return found;
}

}  // namespace corofem
