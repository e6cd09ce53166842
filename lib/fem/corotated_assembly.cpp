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
Vec12 corotated_strain(const TetMesh& mesh, const Tet& t, const Mat3& q, const Eigen::VectorXd& displacement) {
  const Mat3 q_minus_i = q.transpose() - Mat3::Identity();
  const Vec3 u0 = displacement.segment<3>(3 * t[0]);
  Vec12 s;
  s.segment<3>(0).setZero();
  for (int b = 1; b < 4; ++b)
    s.segment<3>(3 * b) =
        q_minus_i * (mesh.rest[t[b]] - mesh.rest[t[0]]) + q.transpose() * (displacement.segment<3>(3 * t[b]) - u0);
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
  for (int a = 0; a < 4; ++a) ks.segment<3>(3 * a) = volumetric * el.gradient[a] + shear * el.gradient[a];
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
void assemble_part_scalar(const std::vector<ElementRest>& elements, const TetMesh& mesh, const AssemblyMap& map,
                          const std::vector<Mat3>& rotations, const Eigen::VectorXd& displacement, int part,
                          double scale, const Eigen::VectorXd* added_diagonal, BrcMatrix& k, Eigen::VectorXd& force) {
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
        if (added_diagonal && b == a && (first >> (5 * a) & 1))  // once a vertex: its block's first store
          rotated.diagonal() += added_diagonal->segment<3>(3 * t[a]);
        if (own.vertex[a]) store_or_add(4 * a + b, rotated);
        if (b != a && own.vertex[b]) store_or_add(4 * b + a, rotated.transpose());
      }
    }
  }
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// dst, a row-major 3x3 block, += (or, for the block's first element, =) the matrix whose rows
/// are lanes 0-2 of r0, r1, r2 (lane 3 zero): repacked into the block's 4 + 4 + 1 layout, two
/// 4-wide adds and one scalar.
__attribute__((target("avx2,fma"))) inline void add_rows_avx2(double* dst, bool first, __m256d r0, __m256d r1,
                                                              __m256d r2) {
  const __m256d v0 = _mm256_blend_pd(r0, _mm256_permute4x64_pd(r1, 0x00), 0b1000);  // r0[0..2], r1[0]
  const __m256d v1 = _mm256_blend_pd(_mm256_permute4x64_pd(r1, 0x09), _mm256_permute4x64_pd(r2, 0x40),
                                     0b1100);  // r1[1], r1[2], r2[0], r2[1]
  const double v2 = _mm_cvtsd_f64(_mm256_extractf128_pd(r2, 1));
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

/// The same part in AVX2. h_a = Q g_a and the force Q (K_e s)_a are 4-wide (lane 3 zero); row r
/// of a block is V lambda h_a[r] h_b + V mu h_b[r] h_a plus the diagonal term in lane r (one
/// multiply, one FMA); a 4x4 transpose of the rows gives the (b, a) block.
__attribute__((target("avx2,fma"))) void assemble_part_avx2(const std::vector<ElementRest>& elements,
                                                            const TetMesh& mesh, const AssemblyMap& map,
                                                            const std::vector<Mat3>& rotations,
                                                            const Eigen::VectorXd& displacement, int part,
                                                            double scale, const Eigen::VectorXd* added_diagonal,
                                                            BrcMatrix& k, Eigen::VectorXd& force) {
  const RowPartition& rows = map.rows;
  const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
  const __m256i first3 = _mm256_set_epi64x(0, -1, -1, -1);
  const __m256d zero = _mm256_setzero_pd();
  const __m256d lane[3] = {_mm256_castsi256_pd(_mm256_set_epi64x(0, 0, 0, -1)),
                           _mm256_castsi256_pd(_mm256_set_epi64x(0, 0, -1, 0)),
                           _mm256_castsi256_pd(_mm256_set_epi64x(0, -1, 0, 0))};
  double* kv = k.values.data();
  for (const int e : rows.elements[part]) {
    const Tet& t = mesh.tets[e];
    const Owned own(t, lo, hi);
    const ElementRest& el = elements[e];
    const double* q = rotations[e].data();  // column-major: Q_rc = q[r + 3 c]
    const __m256d qc[3] = {_mm256_maskload_pd(q, first3), _mm256_maskload_pd(q + 3, first3),
                           _mm256_maskload_pd(q + 6, first3)};
    const auto& blocks = map.block[e];
    const unsigned first = map.first[e];
    const Vec12 ks = stiffness_times(el, corotated_strain(mesh, t, rotations[e], displacement));
    __m256d h[4];
    alignas(32) double lambda_h[4][4], mu_h[4][4];  // scale V lambda h_a and scale V mu h_a
    for (int a = 0; a < 4; ++a) {
      const Vec3& g = el.gradient[a];
      h[a] = _mm256_fmadd_pd(qc[2], _mm256_set1_pd(g[2]),
                             _mm256_fmadd_pd(qc[1], _mm256_set1_pd(g[1]), _mm256_mul_pd(qc[0], _mm256_set1_pd(g[0]))));
      _mm256_store_pd(lambda_h[a], _mm256_mul_pd(_mm256_set1_pd(scale * el.lambda_volume), h[a]));
      _mm256_store_pd(mu_h[a], _mm256_mul_pd(_mm256_set1_pd(scale * el.mu_volume), h[a]));
    }
    for (int a = 0; a < 4; ++a) {
      if (own.vertex[a]) {  // f_a += Q (K_e s)_a
        __m256d fa = _mm256_mul_pd(qc[0], _mm256_set1_pd(ks[3 * a]));
        fa = _mm256_fmadd_pd(qc[1], _mm256_set1_pd(ks[3 * a + 1]), fa);
        fa = _mm256_fmadd_pd(qc[2], _mm256_set1_pd(ks[3 * a + 2]), fa);
        alignas(32) double fa_lanes[4];
        _mm256_store_pd(fa_lanes, fa);
        double* dst = force.data() + 3 * static_cast<std::ptrdiff_t>(t[a]);
        for (int c = 0; c < 3; ++c) dst[c] += fa_lanes[c];
      }
      for (int b = a; b < 4; ++b) {
        if (!own.vertex[a] && !own.vertex[b]) continue;
        const __m256d diagonal = _mm256_set1_pd(scale * el.mu_volume * el.gradient[a].dot(el.gradient[b]));
        __m256d r[3];
        for (int j = 0; j < 3; ++j)
          r[j] = _mm256_add_pd(_mm256_fmadd_pd(_mm256_broadcast_sd(&lambda_h[a][j]), h[b],
                                               _mm256_mul_pd(_mm256_broadcast_sd(&mu_h[b][j]), h[a])),
                               _mm256_and_pd(diagonal, lane[j]));
        if (added_diagonal && b == a && (first >> (5 * a) & 1)) {  // once a vertex: its block's first store
          const __m256d d = _mm256_maskload_pd(added_diagonal->data() + 3 * static_cast<std::ptrdiff_t>(t[a]), first3);
          for (int j = 0; j < 3; ++j) r[j] = _mm256_add_pd(r[j], _mm256_and_pd(d, lane[j]));
        }
        if (own.vertex[a])
          add_rows_avx2(kv + 9 * static_cast<std::size_t>(blocks[4 * a + b]), first >> (4 * a + b) & 1, r[0], r[1], r[2]);
        if (b != a && own.vertex[b]) {
          const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
          const __m256d t2 = _mm256_unpacklo_pd(r[2], zero), t3 = _mm256_unpackhi_pd(r[2], zero);
          add_rows_avx2(kv + 9 * static_cast<std::size_t>(blocks[4 * b + a]), first >> (4 * b + a) & 1,
                        _mm256_permute2f128_pd(t0, t2, 0x20),
                        _mm256_permute2f128_pd(t1, t3, 0x20), _mm256_permute2f128_pd(t0, t2, 0x31));
        }
      }
    }
  }
}
#endif

}  // namespace

void assemble_corotated(const std::vector<ElementRest>& elements, const TetMesh& mesh, const AssemblyMap& map,
                        const std::vector<Mat3>& rotations, const Eigen::VectorXd& displacement, BrcMatrix& k,
                        Eigen::VectorXd& force, double matrix_scale, const Eigen::VectorXd* diagonal) {
  force.resize(3 * static_cast<Eigen::Index>(k.block_rows));
  const RowPartition& rows = map.rows;
  for_each_part(rows, [&](int part) {
    const int lo = rows.row_begin[part], hi = rows.row_begin[part + 1];
    force.segment(3 * lo, 3 * (hi - lo)).setZero();
#ifdef COROFEM_HAVE_AVX2_KERNELS
    if (vector_block_kernels())
      return assemble_part_avx2(elements, mesh, map, rotations, displacement, part, matrix_scale, diagonal, k,
                                force);
#endif
    assemble_part_scalar(elements, mesh, map, rotations, displacement, part, matrix_scale, diagonal, k, force);
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
      const Vec12 ks = stiffness_times(problem.elements[e], corotated_strain(mesh, t, q, displacement));
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
