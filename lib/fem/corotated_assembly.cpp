#include "fem/corotated_assembly.hpp"

#include <algorithm>

#include "sparse/block_kernels.hpp"

namespace corofem {

namespace {

/// Which of an element's vertices lie in [lo, hi): the rows this thread writes.
struct Owned {
  bool vertex[4];
  bool any;
  Owned(const Tet& t, int lo, int hi) : any(false) {
    for (int a = 0; a < 4; ++a) any |= vertex[a] = t[a] >= lo && t[a] < hi;
  }
};

/// s_e = Q^T p_e - x_e up to a translation: s_0 = 0, s_b = (Q^T - I)(x_b - x_0) + Q^T (u_b - u_0).
Vec12 corotated_strain(const TetMesh& mesh, const Tet& t, const Mat3& q,
                       const Eigen::VectorXd& displacement) {
  const Mat3 q_minus_i = q.transpose() - Mat3::Identity();
  const Vec3 u0 = displacement.segment<3>(3 * t[0]);
  Vec12 s;
  s.segment<3>(0).setZero();
  for (int b = 1; b < 4; ++b)
    s.segment<3>(3 * b) = q_minus_i * (mesh.rest[t[b]] - mesh.rest[t[0]]) +
                          q.transpose() * (displacement.segment<3>(3 * t[b]) - u0);
  return s;
}

/// K_e s from the shape gradients (K_ab of element_stiffness.hpp): with G = sum_b s_b g_b^T,
/// (K_e s)_a = V lambda tr(G) g_a + V mu (G + G^T) g_a; s_0 = 0. 14 numbers read, not K_e's 144.
Vec12 stiffness_times(const ElementRest& el, const Vec12& s) {
  Mat3 g = s.segment<3>(3) * el.gradient[1].transpose();
  g.noalias() += s.segment<3>(6) * el.gradient[2].transpose();
  g.noalias() += s.segment<3>(9) * el.gradient[3].transpose();
  const double volumetric = el.lambda_volume * g.trace();
  const Mat3 shear = el.mu_volume * (g + g.transpose());
  Vec12 ks;
  for (int a = 0; a < 4; ++a)
    ks.segment<3>(3 * a) = volumetric * el.gradient[a] + shear * el.gradient[a];
  return ks;
}

// The rotated blocks come from the gradients too: with h_a = Q g_a and Q Q^T = I,
//   Q K_ab Q^T = V lambda h_a h_b^T + V mu h_b h_a^T + V mu (g_a . g_b) I,
// so an element needs Q times its 4 gradients, not 2 x 27 multiply-adds per block and K_e's
// 1152 bytes. Every extractor returns Q orthogonal to 1e-13 (rotation_extractors_test), so this
// is Q K_e Q^T to round-off. The (b, a) block is written as the exact transpose of the (a, b)
// one: K stays exactly symmetric off the diagonal.

/// One part of the assembly: the elements touching rows [lo, hi), each block Q K_ab Q^T added
/// into the rows the part owns, and the element's force Q K_e s_e into the owned vertices'
/// entries. Scalar form: Eigen's 3-vector products.
void assemble_part_scalar(const std::vector<ElementRest>& elements, const TetMesh& mesh,
                          const AssemblyMap& map, const std::vector<Mat3>& rotations,
                          const Eigen::VectorXd& displacement, int part, double scale,
                          const Eigen::VectorXd* added_diagonal, BrcMatrix& k,
                          Eigen::VectorXd& force) {
  const RowPartition& rows = map.rows;
  const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
  for (const int e : rows.elements[part]) {
    const Tet& t = mesh.tets[e];
    const Owned own(t, lo, hi);
    const Mat3& q = rotations[e];
    const ElementRest& el = elements[e];
    const auto& blocks = map.block[e];
    const unsigned first = map.first[e];
    const auto store_or_add = [&](int ab, const Mat3& value) {  // the block's first element stores
      if (first >> ab & 1)
        k.block(blocks[ab]) = value;
      else
        k.block(blocks[ab]) += value;
    };
    const Vec12 ks = stiffness_times(el, corotated_strain(mesh, t, q, displacement));
    Vec3 h[4];
    for (int a = 0; a < 4; ++a) h[a] = q * el.gradient[a];
    for (int a = 0; a < 4; ++a) {
      if (own.vertex[a]) force.segment<3>(3 * t[a]) += q * ks.segment<3>(3 * a);
      for (int b = a; b < 4; ++b) {
        if (!own.vertex[a] && !own.vertex[b]) continue;
        const double lambda = scale * el.lambda_volume, mu = scale * el.mu_volume;
        Mat3 rotated = lambda * h[a] * h[b].transpose();
        rotated.noalias() += mu * h[b] * h[a].transpose();
        rotated.diagonal().array() += mu * el.gradient[a].dot(el.gradient[b]);
        if (added_diagonal && b == a &&
            (first >> (5 * a) & 1))  // once a vertex: its block's first store
          rotated.diagonal() += added_diagonal->segment<3>(3 * t[a]);
        if (own.vertex[a]) store_or_add(4 * a + b, rotated);
        if (b != a && own.vertex[b]) store_or_add(4 * b + a, rotated.transpose());
      }
    }
  }
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// The assembly's K blocks are cold in the step (the Galerkin stream has evicted them) and
/// scattered, so no hardware prefetcher fetches them: the blocks of the element this many places
/// ahead in the part's list are prefetched (BM_CorotatedAssembly/dragon_cold measures it).
constexpr std::size_t kPrefetchAhead = 24;

/// h = Q g_a of one vertex in the lane patterns of a row-major 3x3 block: entry (r, c) of
/// x y^T is x_r y_c, so the block's entries 0-3, (0,0) (0,1) (0,2) (1,0), are P(x) Q(y) and its
/// entries 4-7, (1,1) (1,2) (2,0) (2,1), are S(x) T(y); entry 8 is x_2 y_2. Each pattern also
/// times scale V lambda (l) and scale V mu (m), so that a block is one multiply and one FMA per
/// 4 entries, already in storage order (no repacking).
struct PackedGradient {
  __m256d p, q, s, t;      // h in lanes [0 0 0 1], [0 1 2 0], [1 1 2 2], [1 2 0 1]
  __m256d lp, lq, ls, lt;  // l times those
  __m256d mp, mq, ms, mt;  // m times those
  double h2, lh2, mh2;
};

__attribute__((target("avx2,fma"), always_inline)) inline PackedGradient pack_gradient(__m256d h,
                                                                                       double l,
                                                                                       double m) {
  PackedGradient g;
  const __m256d lv = _mm256_set1_pd(l), mv = _mm256_set1_pd(m);
  g.p = _mm256_permute4x64_pd(h, 0x40);
  g.q = _mm256_permute4x64_pd(h, 0x24);
  g.s = _mm256_permute4x64_pd(h, 0xA5);
  g.t = _mm256_permute4x64_pd(h, 0x49);
  g.lp = _mm256_mul_pd(lv, g.p), g.lq = _mm256_mul_pd(lv, g.q);
  g.ls = _mm256_mul_pd(lv, g.s), g.lt = _mm256_mul_pd(lv, g.t);
  g.mp = _mm256_mul_pd(mv, g.p), g.mq = _mm256_mul_pd(mv, g.q);
  g.ms = _mm256_mul_pd(mv, g.s), g.mt = _mm256_mul_pd(mv, g.t);
  g.h2 = _mm_cvtsd_f64(_mm256_extractf128_pd(h, 1));
  g.lh2 = l * g.h2, g.mh2 = m * g.h2;
  return g;
}

/// Columns c0, c1, c2 (lane 3 zero) of a 3x3 matrix to its rows (lane 3 zero).
__attribute__((target("avx2,fma"), always_inline)) inline void transpose3_avx2(const __m256d c[3],
                                                                               __m256d r[3]) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d lo01 = _mm256_unpacklo_pd(c[0], c[1]), hi01 = _mm256_unpackhi_pd(c[0], c[1]);
  const __m256d lo2 = _mm256_unpacklo_pd(c[2], zero), hi2 = _mm256_unpackhi_pd(c[2], zero);
  r[0] = _mm256_permute2f128_pd(lo01, lo2, 0x20);
  r[1] = _mm256_permute2f128_pd(hi01, hi2, 0x20);
  r[2] = _mm256_permute2f128_pd(lo01, lo2, 0x31);
}

/// p[0..2] in lanes 0-2, lane 3 zero.
__attribute__((target("avx2,fma"), always_inline)) inline __m256d load3_avx2(const double* p) {
  return _mm256_maskload_pd(p, _mm256_set_epi64x(0, -1, -1, -1));
}

/// Lane i of v in all four lanes.
template <int i>
__attribute__((target("avx2,fma"), always_inline)) inline __m256d lane_avx2(__m256d v) {
  return _mm256_permute4x64_pd(v, i * 0x55);
}

/// The element's force Q (K_e s_e)_a, a = 0..3 (lane 3 zero): corotated_strain and
/// stiffness_times in 4-wide form, the same formulas summed in another order (round-off).
/// qc: Q's columns.
__attribute__((target("avx2,fma"), always_inline)) inline void element_force_avx2(
    const TetMesh& mesh, const Tet& t, const ElementRest& el, const __m256d qc[3], const double* u,
    __m256d f[4]) {
  __m256d qt[3];  // Q^T's columns: Q's rows
  transpose3_avx2(qc, qt);
  const __m256d e[3] = {_mm256_set_pd(0, 0, 0, 1), _mm256_set_pd(0, 0, 1, 0),
                        _mm256_set_pd(0, 1, 0, 0)};
  const __m256d qt_minus_i[3] = {_mm256_sub_pd(qt[0], e[0]), _mm256_sub_pd(qt[1], e[1]),
                                 _mm256_sub_pd(qt[2], e[2])};
  const __m256d x0 = load3_avx2(mesh.rest[t[0]].data()),
                u0 = load3_avx2(u + 3 * static_cast<std::ptrdiff_t>(t[0]));
  __m256d g[3];  // G = sum_b s_b g_b^T by columns, s_b = (Q^T - I)(x_b - x_0) + Q^T (u_b - u_0)
  for (int b = 1; b < 4; ++b) {
    const __m256d dx = _mm256_sub_pd(load3_avx2(mesh.rest[t[b]].data()), x0);
    const __m256d du = _mm256_sub_pd(load3_avx2(u + 3 * static_cast<std::ptrdiff_t>(t[b])), u0);
    __m256d sb = _mm256_mul_pd(qt_minus_i[0], lane_avx2<0>(dx));
    sb = _mm256_fmadd_pd(qt_minus_i[1], lane_avx2<1>(dx), sb);
    sb = _mm256_fmadd_pd(qt_minus_i[2], lane_avx2<2>(dx), sb);
    sb = _mm256_fmadd_pd(qt[0], lane_avx2<0>(du), sb);
    sb = _mm256_fmadd_pd(qt[1], lane_avx2<1>(du), sb);
    sb = _mm256_fmadd_pd(qt[2], lane_avx2<2>(du), sb);
    const double* gb = el.gradient[b].data();
    for (int c = 0; c < 3; ++c) {
      const __m256d gbc = _mm256_broadcast_sd(gb + c);
      g[c] = b == 1 ? _mm256_mul_pd(sb, gbc) : _mm256_fmadd_pd(sb, gbc, g[c]);
    }
  }
  alignas(32) double diagonal[3][4];
  for (int c = 0; c < 3; ++c) _mm256_store_pd(diagonal[c], g[c]);
  const double trace = diagonal[0][0] + diagonal[1][1] + diagonal[2][2];
  const __m256d volumetric = _mm256_set1_pd(el.lambda_volume * trace);
  __m256d gt[3];
  transpose3_avx2(g, gt);
  const __m256d mu = _mm256_set1_pd(el.mu_volume);
  const __m256d shear[3] = {_mm256_mul_pd(mu, _mm256_add_pd(g[0], gt[0])),
                            _mm256_mul_pd(mu, _mm256_add_pd(g[1], gt[1])),
                            _mm256_mul_pd(mu, _mm256_add_pd(g[2], gt[2]))};
  for (int a = 0; a < 4;
       ++a) {  // (K_e s)_a = V lambda tr(G) g_a + V mu (G + G^T) g_a, then Q times it
    const double* ga = el.gradient[a].data();
    __m256d ks = _mm256_mul_pd(volumetric, load3_avx2(ga));
    for (int c = 0; c < 3; ++c) ks = _mm256_fmadd_pd(shear[c], _mm256_broadcast_sd(ga + c), ks);
    __m256d fa = _mm256_mul_pd(qc[0], lane_avx2<0>(ks));
    fa = _mm256_fmadd_pd(qc[1], lane_avx2<1>(ks), fa);
    f[a] = _mm256_fmadd_pd(qc[2], lane_avx2<2>(ks), fa);
  }
}

/// dst, a row-major 3x3 block, += (or, for the block's first element, =) v0 | v1 | v2.
__attribute__((target("avx2,fma"), always_inline)) inline void add_block_avx2(
    double* dst, bool first, __m256d v0, __m256d v1, double v2) {
  if (first) {
    _mm256_storeu_pd(dst, v0);
    _mm256_storeu_pd(dst + 4, v1);
    dst[8] = v2;
    return;
  }
  _mm256_storeu_pd(dst, _mm256_add_pd(_mm256_loadu_pd(dst), v0));
  _mm256_storeu_pd(dst + 4, _mm256_add_pd(_mm256_loadu_pd(dst + 4), v1));
  dst[8] += v2;
}

/// The same part in AVX2. h_a = Q g_a and the force Q (K_e s)_a are 4-wide (lane 3 zero). Block
/// (a, b) is l h_a h_b^T + m h_b h_a^T + d I (d = m g_a . g_b) in storage order from the packed
/// patterns; block (b, a) takes entry (r, c) from the same operands as (a, b)'s entry (c, r), so
/// it is (a, b)'s exact transpose, and both have the scalar form's roundings: the same bits.
__attribute__((target("avx2,fma"))) void assemble_part_avx2(
    const std::vector<ElementRest>& elements, const TetMesh& mesh, const AssemblyMap& map,
    const std::vector<Mat3>& rotations, const Eigen::VectorXd& displacement, int part, double scale,
    const Eigen::VectorXd* added_diagonal, BrcMatrix& k, Eigen::VectorXd& force) {
  const RowPartition& rows = map.rows;
  const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
  const __m256d lane0 = _mm256_castsi256_pd(_mm256_set_epi64x(0, 0, 0, -1));
  double* kv = k.values.data();
  const std::vector<int>& list = rows.elements[part];
  for (std::size_t n = 0; n < list.size(); ++n) {
    const int e = list[n];
    if (n + kPrefetchAhead < list.size()) {  // a block's 72 bytes span up to two lines
      const auto& ahead = map.block[list[n + kPrefetchAhead]];
      for (int ab = 0; ab < 16; ++ab) {
        const char* blk =
            reinterpret_cast<const char*>(kv + 9 * static_cast<std::size_t>(ahead[ab]));
        _mm_prefetch(blk, _MM_HINT_T0);
        _mm_prefetch(blk + 71, _MM_HINT_T0);  // its last byte: within the values
      }
    }
    const Tet& t = mesh.tets[e];
    const Owned own(t, lo, hi);
    const ElementRest& el = elements[e];
    const double* q = rotations[e].data();  // column-major: Q_rc = q[r + 3 c]
    const __m256d qc[3] = {load3_avx2(q), load3_avx2(q + 3), load3_avx2(q + 6)};
    const auto& blocks = map.block[e];
    const unsigned first = map.first[e];
    __m256d f[4];
    element_force_avx2(mesh, t, el, qc, displacement.data(), f);
    const double l = scale * el.lambda_volume, m = scale * el.mu_volume;
    PackedGradient h[4];
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) {
      const Vec3& g = el.gradient[a];
      const __m256d ha = _mm256_fmadd_pd(
          qc[2], _mm256_set1_pd(g[2]),
          _mm256_fmadd_pd(qc[1], _mm256_set1_pd(g[1]), _mm256_mul_pd(qc[0], _mm256_set1_pd(g[0]))));
      h[a] = pack_gradient(ha, l, m);
      if (own.vertex[a]) {  // f_a += Q (K_e s)_a
        alignas(32) double fa_lanes[4];
        _mm256_store_pd(fa_lanes, f[a]);
        double* dst = force.data() + 3 * static_cast<std::ptrdiff_t>(t[a]);
        for (int c = 0; c < 3; ++c) dst[c] += fa_lanes[c];
      }
    }
#pragma GCC unroll 4
    for (int a = 0; a < 4; ++a) {
#pragma GCC unroll 4
      for (int b = a; b < 4; ++b) {
        if (!own.vertex[a] && !own.vertex[b]) continue;
        const PackedGradient &x = h[a], &y = h[b];
        const double d = m * el.gradient[a].dot(el.gradient[b]);
        const __m256d d0 = _mm256_and_pd(_mm256_set1_pd(d), lane0);
        __m256d v0 = _mm256_add_pd(_mm256_fmadd_pd(x.lp, y.q, _mm256_mul_pd(y.mp, x.q)), d0);
        __m256d v1 = _mm256_add_pd(_mm256_fmadd_pd(x.ls, y.t, _mm256_mul_pd(y.ms, x.t)), d0);
        double v2 = _mm_cvtsd_f64(_mm_fmadd_sd(_mm_set_sd(x.lh2), _mm_set_sd(y.h2),
                                               _mm_set_sd(y.mh2 * x.h2))) +
                    d;
        if (added_diagonal && b == a &&
            (first >> (5 * a) & 1)) {  // once a vertex: its block's first store
          const double* dd = added_diagonal->data() + 3 * static_cast<std::ptrdiff_t>(t[a]);
          v0 = _mm256_add_pd(v0, _mm256_and_pd(_mm256_set1_pd(dd[0]), lane0));
          v1 = _mm256_add_pd(v1, _mm256_and_pd(_mm256_set1_pd(dd[1]), lane0));
          v2 += dd[2];
        }
        if (own.vertex[a])
          add_block_avx2(kv + 9 * static_cast<std::size_t>(blocks[4 * a + b]),
                         first >> (4 * a + b) & 1, v0, v1, v2);
        if (b != a && own.vertex[b]) {
          const __m256d w0 =
              _mm256_add_pd(_mm256_fmadd_pd(x.lq, y.p, _mm256_mul_pd(y.mq, x.p)), d0);
          const __m256d w1 =
              _mm256_add_pd(_mm256_fmadd_pd(x.lt, y.s, _mm256_mul_pd(y.mt, x.s)), d0);
          add_block_avx2(kv + 9 * static_cast<std::size_t>(blocks[4 * b + a]),
                         first >> (4 * b + a) & 1, w0, w1, v2);
        }
      }
    }
  }
}
#endif

}  // namespace

void assemble_corotated(const std::vector<ElementRest>& elements, const TetMesh& mesh,
                        const AssemblyMap& map, const std::vector<Mat3>& rotations,
                        const Eigen::VectorXd& displacement, BrcMatrix& k, Eigen::VectorXd& force,
                        double matrix_scale, const Eigen::VectorXd* diagonal) {
  force.resize(3 * static_cast<Eigen::Index>(k.block_rows));
  const RowPartition& rows = map.rows;
  for_each_part(rows, [&](int part) {
    const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
    force.segment(3 * lo, 3 * (hi - lo)).setZero();
#ifdef COROFEM_HAVE_AVX2_KERNELS
    if (vector_block_kernels())
      return assemble_part_avx2(elements, mesh, map, rotations, displacement, part, matrix_scale,
                                diagonal, k, force);
#endif
    assemble_part_scalar(elements, mesh, map, rotations, displacement, part, matrix_scale, diagonal,
                         k, force);
  });
}

Eigen::VectorXd internal_forces(const FeProblem& problem, const std::vector<Mat3>& rotations,
                                const Eigen::VectorXd& displacement) {
  const TetMesh& mesh = problem.mesh;
  const RowPartition& rows = problem.assembly.rows;
  Eigen::VectorXd f(3 * mesh.num_vertices());
  for_each_part(rows, [&](int part) {
    const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
    f.segment(3 * lo, 3 * (hi - lo)).setZero();
    for (const int e : rows.elements[part]) {
      const Tet& t = mesh.tets[e];
      const Owned own(t, lo, hi);
      const Mat3& q = rotations[e];
      const Vec12 ks =
          stiffness_times(problem.elements[e], corotated_strain(mesh, t, q, displacement));
      for (int a = 0; a < 4; ++a)
        if (own.vertex[a]) f.segment<3>(3 * t[a]) += q * ks.segment<3>(3 * a);
    }
  });
  return f;
}

double elastic_energy(const std::vector<ElementRest>& elements, const TetMesh& mesh,
                      const std::vector<Mat3>& rotations, const Eigen::VectorXd& displacement) {
  double energy = 0;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Vec12 s = corotated_strain(mesh, mesh.tets[e], rotations[e], displacement);
    energy += 0.5 * s.dot(stiffness_times(elements[e], s));
  }
  return energy;
}

}  // namespace corofem
