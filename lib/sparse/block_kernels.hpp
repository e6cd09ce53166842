#pragma once
// The inner loops of the passes over 3x3 blocks: the row sum s = sum_k A_k x_{col k} over a run
// of one row's blocks (the product, the V-cycle's residual, the Gauss-Seidel sweeps), and the
// weighted block add E_b += w A_k (the Galerkin stream's scatter). The assembly's AVX2 form of
// Q K_ab Q^T (fem/corotated_assembly.cpp) is switched with them.
// A product is bound by instruction throughput, not by memory: scalar code issues some 25
// instructions per block, the AVX2 form 7 (BM_BlockKernels: the product 1.4-1.6x faster at 1 and
// 2 threads; single-precision blocks, half the bytes, were no faster where the matrices sit in
// the L3, and no faster a step where they gained: lib/README "Multigrid"). Each block row is one
// 4-wide load (the fourth lane, the next row's first entry, meets a zero lane of x and is
// dropped), multiplied by x_j and added into one accumulator per block row; the three lanes are
// summed when the row ends. Chosen once, at run time, on CPUs with AVX2 and FMA; the scalar form
// is the portable one. The two sum in different orders, so they agree to round-off, not in bits;
// every caller uses one form in a process (its bits then do not depend on the threads).
// The Galerkin stream's scatter likewise: 9 scalar multiply-adds a pair against 2 4-wide FMAs
// and one scalar (the update's Galerkin part is bound by those instructions). The FMA rounds once
// where the scalar form rounds twice: round-off again.
// The Gauss-Seidel sweeps read values stored a few rows before: there x_j is put together from
// 8-byte loads, because one 4-wide load over three 8-byte stores still in flight cannot be
// forwarded from them (that form was slower than the scalar sweeps). The sweeps gain more inside
// the step, where their rows are partly cached, than in BM_BlockKernels' isolated sweeps.
#include <cstddef>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define COROFEM_HAVE_AVX2_KERNELS 1
#endif

namespace corofem {

namespace detail {
extern bool vector_block_kernels_on;
}
/// Whether the block passes use the AVX2/FMA form (this CPU has it, and it is not switched off).
inline bool vector_block_kernels() {
  return detail::vector_block_kernels_on;
}
/// Switches the AVX2 form off (false) or back on where the CPU has it; for tests and
/// comparisons. Returns the previous setting.
bool set_vector_block_kernels(bool on);
/// "avx2-fma" or "scalar": the form in use, for the records.
const char* block_kernels_name();

/// s = sum of A_k x_{col k} over blocks [begin, end) of row-major 3x3 values v, x_j at
/// source(j) (3 doubles); Backward: the blocks from end - 1 down to begin (a backward sweep then
/// streams the matrix downwards, as the hardware prefetchers expect). Scalar form: each row's
/// three terms summed left to right, block by block.
template <bool Backward, class Source>
inline void block_row_sum_scalar(const int* col, const double* v, int begin, int end,
                                 const Source& source, double s[3]) {
  double s0 = 0, s1 = 0, s2 = 0;
  for (int n = begin; n < end; ++n) {
    const int k = Backward ? end - 1 - (n - begin) : n;
    const double* xj = source(col[k]);
    const double* m = v + 9 * static_cast<std::ptrdiff_t>(k);
    s0 += m[0] * xj[0] + m[1] * xj[1] + m[2] * xj[2];
    s1 += m[3] * xj[0] + m[4] * xj[1] + m[5] * xj[2];
    s2 += m[6] * xj[0] + m[7] * xj[1] + m[8] * xj[2];
  }
  s[0] = s0;
  s[1] = s1;
  s[2] = s2;
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// The same sum in AVX2 (see the file comment): per block row one lane-wise product with x_j,
/// the lanes added at the end ((l0 + l1) + l2). The third block row and x_j are masked loads,
/// so nothing past the last block or the last vertex is read.
/// Backward: the blocks from end - 1 down; Fresh: x holds values stored a few rows before (a
/// sweep), so x_j is put together from 8-byte loads, which the stores can forward to.
template <bool Backward = false, bool Fresh = false, class Source>
__attribute__((target("avx2,fma"))) inline void block_row_sum_avx2(const int* col, const double* v,
                                                                   int begin, int end,
                                                                   const Source& source,
                                                                   double s[3]) {
  const __m256i first3 = _mm256_set_epi64x(0, -1, -1, -1);
  __m256d a0 = _mm256_setzero_pd(), a1 = a0, a2 = a0;
  for (int n = begin; n < end; ++n) {
    const int k = Backward ? end - 1 - (n - begin) : n;
    const double* m = v + 9 * static_cast<std::ptrdiff_t>(k);
    const double* xj = source(col[k]);
    const __m256d x =
        Fresh ? _mm256_set_pd(0.0, xj[2], xj[1], xj[0]) : _mm256_maskload_pd(xj, first3);
    a0 = _mm256_fmadd_pd(_mm256_loadu_pd(m), x, a0);
    a1 = _mm256_fmadd_pd(_mm256_loadu_pd(m + 3), x, a1);
    a2 = _mm256_fmadd_pd(_mm256_maskload_pd(m + 6, first3), x, a2);
  }
  alignas(32) double l[3][4];
  _mm256_store_pd(l[0], a0);
  _mm256_store_pd(l[1], a1);
  _mm256_store_pd(l[2], a2);
  for (int c = 0; c < 3; ++c) s[c] = (l[c][0] + l[c][1]) + l[c][2];
}
#endif

/// The sum in the form chosen for this process (Backward and Fresh as for the AVX2 form).
template <bool Backward = false, bool Fresh = false, class Source>
inline void block_row_sum(const int* col, const double* v, int begin, int end, const Source& source,
                          double s[3]) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels())
    return block_row_sum_avx2<Backward, Fresh>(col, v, begin, end, source, s);
#endif
  block_row_sum_scalar<Backward>(col, v, begin, end, source, s);
}

/// y_j += A_kj^T x_k over the blocks [begin, end) of row k (columns j): for a symmetric matrix
/// these are the blocks A_jk = A_kj^T of column k, so a sweep that reads row k can add x_k's
/// part of (A x)_j for the rows j it will not read again. Scalar form.
inline void add_transposed_row_scalar(const int* col, const double* v, int begin, int end,
                                      const double* xk, double* y) {
  for (int n = begin; n < end; ++n) {
    const double* m = v + 9 * static_cast<std::ptrdiff_t>(n);
    double* yj = y + 3 * col[n];
    yj[0] += m[0] * xk[0] + m[3] * xk[1] + m[6] * xk[2];
    yj[1] += m[1] * xk[0] + m[4] * xk[1] + m[7] * xk[2];
    yj[2] += m[2] * xk[0] + m[5] * xk[1] + m[8] * xk[2];
  }
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// The same in AVX2: A^T x as x_0 (row 0) + x_1 (row 1) + x_2 (row 2), three FMAs a block (the
/// scalar form, with its 9 loads and 3 reductions a block, made the fused sweep slower than a
/// sweep and a separate product).
__attribute__((target("avx2,fma"))) inline void add_transposed_row_avx2(const int* col,
                                                                        const double* v, int begin,
                                                                        int end, const double* xk,
                                                                        double* y) {
  const __m256i first3 = _mm256_set_epi64x(0, -1, -1, -1);
  const __m256d x0 = _mm256_broadcast_sd(xk), x1 = _mm256_broadcast_sd(xk + 1),
                x2 = _mm256_broadcast_sd(xk + 2);
  for (int n = begin; n < end; ++n) {
    const double* m = v + 9 * static_cast<std::ptrdiff_t>(n);
    __m256d t = _mm256_mul_pd(_mm256_loadu_pd(m), x0);
    t = _mm256_fmadd_pd(_mm256_loadu_pd(m + 3), x1, t);
    t = _mm256_fmadd_pd(_mm256_maskload_pd(m + 6, first3), x2, t);
    alignas(32) double l[4];
    _mm256_store_pd(l, t);
    double* yj = y + 3 * col[n];
    yj[0] += l[0];
    yj[1] += l[1];
    yj[2] += l[2];
  }
}
#endif

/// The transposed row in the form chosen for this process.
inline void add_transposed_row(const int* col, const double* v, int begin, int end,
                               const double* xk, double* y) {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  if (vector_block_kernels()) return add_transposed_row_avx2(col, v, begin, end, xk, y);
#endif
  add_transposed_row_scalar(col, v, begin, end, xk, y);
}

/// e += w a over the 9 entries of a block, in the scalar form (each entry rounded twice).
inline void add_scaled_block_scalar(double* e, double w, const double* a) {
  for (int m = 0; m < 9; ++m) e[m] += w * a[m];
}

#ifdef COROFEM_HAVE_AVX2_KERNELS
/// The same in AVX2: two 4-wide FMAs and one scalar one.
__attribute__((target("avx2,fma"))) inline void add_scaled_block_avx2(double* e, double w,
                                                                      const double* a) {
  const __m256d weight = _mm256_set1_pd(w);
  _mm256_storeu_pd(e, _mm256_fmadd_pd(weight, _mm256_loadu_pd(a), _mm256_loadu_pd(e)));
  _mm256_storeu_pd(e + 4, _mm256_fmadd_pd(weight, _mm256_loadu_pd(a + 4), _mm256_loadu_pd(e + 4)));
  e[8] = __builtin_fma(w, a[8], e[8]);
}
#endif

}  // namespace corofem
