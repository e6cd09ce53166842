#include "mesh/surface_simplification.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

namespace corofem {

namespace {

using Quadric = Eigen::Matrix4d;

/// Weight of an edge's length^4 beside its quadric error (both area x distance^2). Measured on
/// the models' derived levels (MG-PCG iterations a step, bunny / horse / dragon report scenes):
/// 0.01: 6 / 7 / 13; 0.1: 6 / 6 / 10.5; 1: 6 / 6 / 9 (the dragon's given levels: 10.7); 3: 6 / 6 /
/// 11. Even spacing matters more than features here; a collapse across a sharp edge still adds
/// its quadric error, and a cube keeps its corners (SurfaceSimplification gates).
constexpr double kLengthWeight = 1.0;
using Triangle = std::array<int, 3>;

/// 4 sqrt(3) area / sum of squared edges: 1 for an equilateral triangle, 0 for a degenerate one.
double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c, Vec3* normal) {
  const Vec3 n = (b - a).cross(c - a);
  if (normal) *normal = n;
  const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return edges > 0 ? 2 * std::sqrt(3.0) * n.norm() / edges : 0;
}

struct Collapse {
  double cost;
  int u, v;
  unsigned stamp_u, stamp_v;
  Vec3 position;
  bool operator>(const Collapse& other) const { return cost > other.cost; }
};

class Simplifier {
 public:
  explicit Simplifier(const SurfaceMesh& s)
      : points_(s.points),
        triangles_(s.triangles),
        triangle_alive_(s.triangles.size(), 1),
        vertex_alive_(s.points.size(), 1),
        stamp_(s.points.size(), 0),
        faces_of_(s.points.size()),
        quadric_(s.points.size(), Quadric::Zero()),
        alive_(s.num_vertices()) {
    for (int f = 0; f < static_cast<int>(triangles_.size()); ++f) {
      const Triangle& t = triangles_[f];
      Vec3 n;
      triangle_quality(points_[t[0]], points_[t[1]], points_[t[2]], &n);
      const double twice_area = n.norm();
      if (twice_area == 0) continue;
      n /= twice_area;
      const Eigen::Vector4d plane(n.x(), n.y(), n.z(), -n.dot(points_[t[0]]));
      // Area-weighted plane quadrics (Garland and Heckbert, section 6.1).
      const Quadric k = 0.5 * twice_area * plane * plane.transpose();
      for (int c = 0; c < 3; ++c) {
        quadric_[t[c]] += k;
        faces_of_[t[c]].push_back(f);
      }
    }
    for (const Triangle& t : triangles_)
      for (int c = 0; c < 3; ++c)
        if (t[c] < t[(c + 1) % 3]) push(t[c], t[(c + 1) % 3]);
  }

  void run(int target, SimplificationStats& stats) {
    while (alive_ > target && !heap_.empty()) {
      const Collapse c = heap_.top();
      heap_.pop();
      if (!vertex_alive_[c.u] || !vertex_alive_[c.v] || stamp_[c.u] != c.stamp_u ||
          stamp_[c.v] != c.stamp_v)
        continue;  // an end point moved since: its edges were queued again
      if (!allowed(c.u, c.v, c.position)) {
        ++stats.rejected;
        continue;
      }
      collapse(c.u, c.v, c.position);
      ++stats.collapses;
    }
  }

  SurfaceMesh result() const {
    SurfaceMesh out;
    std::vector<int> index(points_.size(), -1);
    for (std::size_t v = 0; v < points_.size(); ++v)
      if (vertex_alive_[v]) {
        index[v] = out.num_vertices();
        out.points.push_back(points_[v]);
      }
    for (std::size_t f = 0; f < triangles_.size(); ++f)
      if (triangle_alive_[f]) {
        const Triangle& t = triangles_[f];
        out.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
      }
    return out;
  }

 private:
  std::vector<int> neighbours(int u) const {
    std::vector<int> n;
    for (int f : faces_of_[u])
      if (triangle_alive_[f])
        for (int w : triangles_[f])
          if (w != u) n.push_back(w);
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  }

  /// The point of least error on the edge's quadric; an end point or the midpoint where the
  /// quadric is singular (flat) or its minimum lies off the edge's neighbourhood.
  void push(int u, int v) {
    const Quadric q = quadric_[u] + quadric_[v];
    const auto error = [&q](const Vec3& p) {
      const Eigen::Vector4d h(p.x(), p.y(), p.z(), 1);
      return h.dot(q * h);
    };
    const Vec3 a = points_[u], b = points_[v];
    Vec3 best = 0.5 * (a + b);
    double cost = error(best);
    for (const Vec3& p : {a, b})
      if (error(p) < cost) cost = error(p), best = p;
    const Eigen::Matrix3d m = q.topLeftCorner<3, 3>();
    Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
    if (lu.rank() == 3) {
      const Vec3 p = lu.solve(-q.topRightCorner<3, 1>());
      if ((p - best).norm() < (a - b).norm() && error(p) < cost) cost = error(p), best = p;
    }
    // Edge length as a tie-breaker: on flat or gently curved parts the quadric error is near zero
    // for every collapse; the shortest edges then go first, keeping the triangles' spacing even
    // (a level's coarse tets follow its surface triangles' shape).
    const double length2 = (a - b).squaredNorm();
    heap_.push({std::max(cost, 0.0) + kLengthWeight * length2 * length2, u, v, stamp_[u], stamp_[v],
                best});
  }

  bool allowed(int u, int v, const Vec3& p) const {
    const std::vector<int> nu = neighbours(u), nv = neighbours(v);
    std::vector<int> common;
    std::set_intersection(nu.begin(), nu.end(), nv.begin(), nv.end(), std::back_inserter(common));
    if (common.size() != 2) return false;  // link condition: the surface would pinch
    for (int w : common)
      if (neighbours(w).size() <= 3) return false;
    for (int end : {u, v})
      for (int f : faces_of_[end]) {
        if (!triangle_alive_[f]) continue;
        const Triangle& t = triangles_[f];
        if (std::find(t.begin(), t.end(), u) != t.end() &&
            std::find(t.begin(), t.end(), v) != t.end())
          continue;  // removed by the collapse
        Vec3 before, after;
        std::array<Vec3, 3> x{points_[t[0]], points_[t[1]], points_[t[2]]};
        const double q_before = triangle_quality(x[0], x[1], x[2], &before);
        for (int c = 0; c < 3; ++c)
          if (t[c] == end) x[c] = p;
        const double q_after = triangle_quality(x[0], x[1], x[2], &after);
        if (after.dot(before) < 0.5 * after.norm() * before.norm()) return false;  // > 60 degrees
        if (q_after < 0.1 && q_after < q_before) return false;                     // sliver
      }
    return true;
  }

  void collapse(int u, int v, const Vec3& p) {
    points_[u] = p;
    quadric_[u] += quadric_[v];
    for (int f : faces_of_[v]) {
      if (!triangle_alive_[f]) continue;
      Triangle& t = triangles_[f];
      if (std::find(t.begin(), t.end(), u) != t.end()) {
        triangle_alive_[f] = 0;
        continue;
      }
      for (int& c : t)
        if (c == v) c = u;
      faces_of_[u].push_back(f);
    }
    faces_of_[u].erase(std::remove_if(faces_of_[u].begin(), faces_of_[u].end(),
                                      [&](int f) { return !triangle_alive_[f]; }),
                       faces_of_[u].end());
    faces_of_[v].clear();
    vertex_alive_[v] = 0;
    --alive_;
    ++stamp_[u];
    for (int w : neighbours(u)) push(std::min(u, w), std::max(u, w));
  }

  std::vector<Vec3> points_;
  std::vector<Triangle> triangles_;
  std::vector<char> triangle_alive_, vertex_alive_;
  std::vector<unsigned> stamp_;
  std::vector<std::vector<int>> faces_of_;
  std::vector<Quadric> quadric_;
  int alive_;
  std::priority_queue<Collapse, std::vector<Collapse>, std::greater<Collapse>> heap_;
};

}  // namespace

namespace {

/// Area-weighted vertex normals (unit; zero for a vertex of no triangle).
std::vector<Vec3> vertex_normals(const SurfaceMesh& s) {
  std::vector<Vec3> normals(s.points.size(), Vec3::Zero());
  for (const auto& t : s.triangles) {
    const Vec3 n = (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
    for (int v : t) normals[v] += n;
  }
  for (Vec3& n : normals)
    if (n.norm() > 0) n.normalize();
  return normals;
}

/// Nearest point of a set by a uniform grid of buckets (rings searched outward until the ring
/// distance exceeds the best found).
class NearestPoint {
 public:
  NearestPoint(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      buckets_[key(cell_of(points[i]))].push_back(i);
      lo = lo.cwiseMin(points[i]);
      hi = hi.cwiseMax(points[i]);
    }
    max_ring_ = points.empty() ? 0 : 2 + static_cast<int>((hi - lo).maxCoeff() / cell);
  }
  int operator()(const Vec3& x) const {
    const Eigen::Vector3i c = cell_of(x);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    // Points in ring r are at least (r - 1) cells away.
    for (int ring = 0; ring <= max_ring_; ++ring) {
      if (best >= 0 && (ring - 1) * cell_ > std::sqrt(best_d2)) break;
      for (int i = -ring; i <= ring; ++i)
        for (int j = -ring; j <= ring; ++j)
          for (int k = -ring; k <= ring; ++k) {
            if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != ring) continue;
            const auto it = buckets_.find(key(c + Eigen::Vector3i(i, j, k)));
            if (it == buckets_.end()) continue;
            for (int p : it->second) {
              const double d2 = (points_[p] - x).squaredNorm();
              if (d2 < best_d2) best_d2 = d2, best = p;
            }
          }
    }
    return best;
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& x) const { return (x / cell_).array().floor().cast<int>(); }
  static long long key(const Eigen::Vector3i& c) {
    return (static_cast<long long>(c.x() & 0xFFFFF) << 40) |
           (static_cast<long long>(c.y() & 0xFFFFF) << 20) | (c.z() & 0xFFFFF);
  }
  const std::vector<Vec3>& points_;
  double cell_;
  int max_ring_ = 0;  ///< beyond it no ring holds a point (for queries near the points' box)
  std::unordered_map<long long, std::vector<int>> buckets_;
};

double mean_edge(const SurfaceMesh& s) {
  double sum = 0;
  for (const auto& t : s.triangles)
    for (int c = 0; c < 3; ++c) sum += (s.points[t[c]] - s.points[t[(c + 1) % 3]]).norm();
  return s.triangles.empty() ? 0 : sum / (3.0 * s.triangles.size());
}

}  // namespace

std::vector<Vec3> covering_moves(const SurfaceMesh& coarse, const SurfaceMesh& fine) {
  const std::vector<Vec3> normals = vertex_normals(coarse);
  const NearestPoint nearest(coarse.points, std::max(mean_edge(coarse), 1e-12));
  std::vector<double> distance(coarse.points.size(), 0.0);
  for (const Vec3& x : fine.points) {
    const int c = nearest(x);
    if (c >= 0) distance[c] = std::max(distance[c], (x - coarse.points[c]).dot(normals[c]));
  }
  std::vector<Vec3> moves(coarse.points.size());
  for (std::size_t v = 0; v < moves.size(); ++v) moves[v] = distance[v] * normals[v];
  return moves;
}

SurfaceMesh simplify_surface(const SurfaceMesh& surface, int target_vertices,
                             SimplificationStats* stats) {
  SimplificationStats local;
  Simplifier simplifier(surface);
  simplifier.run(target_vertices, stats ? *stats : local);
  return simplifier.result();
}

}  // namespace corofem
