#pragma once
// Issue 36's "hierarchy in single precision under a double-precision CG", measured before it is
// built: the fine level's block product and a pair of Gauss-Seidel sweeps with the blocks and
// vectors in float, against double (BM_BlockKernels' *_float counters), and the sweeps with only
// the blocks in float (*_mixed). Measurement only: the library keeps double. Each pass is one
// template instantiated for each (the product threaded as BrcMatrix::multiply, the sweeps in
// natural order with the block-diagonal inverse), so they differ only in the width of the numbers
// they read (the compiler vectorizes them alike).
#include <Eigen/Dense>
#include <vector>

#include "core/threads.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem::bench {

/// A BRC matrix's values and diagonal inverses in T (the pattern read from the matrix itself).
template <class T>
struct BlocksIn {
  const BrcMatrix* a = nullptr;
  std::vector<T> values, inverse_diagonal;  // 9 per block, 9 per block row
  std::vector<int> diagonal;                // index of each row's diagonal block

  explicit BlocksIn(const BrcMatrix& m) : a(&m), values(m.values.begin(), m.values.end()) {
    inverse_diagonal.resize(9 * static_cast<std::size_t>(m.block_rows));
    diagonal.resize(m.block_rows);
    for (int i = 0; i < m.block_rows; ++i) {
      diagonal[i] = m.find(i, i);
      const Eigen::Matrix3d inverse = m.block(diagonal[i]).inverse();
      for (int e = 0; e < 9; ++e)
        inverse_diagonal[9 * i + e] = static_cast<T>(inverse(e / 3, e % 3));
    }
  }
};

/// y = A x, threaded over rows as BrcMatrix::multiply is, each row's sum in the scalar form.
template <class T>
inline void multiply(const BlocksIn<T>& m, const T* x, T* y) {
  const BrcMatrix& a = *m.a;
#pragma omp parallel for schedule(static) num_threads(threads_for(a.num_blocks()))
  for (int i = 0; i < a.block_rows; ++i) {
    T s[3] = {0, 0, 0};
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      const T* v = m.values.data() + 9 * static_cast<std::ptrdiff_t>(k);
      const T* xj = x + 3 * a.col_index[k];
      for (int r = 0; r < 3; ++r)
        s[r] += v[3 * r] * xj[0] + v[3 * r + 1] * xj[1] + v[3 * r + 2] * xj[2];
    }
    for (int r = 0; r < 3; ++r) y[3 * i + r] = s[r];
  }
}

/// One block Gauss-Seidel row: x_i = D_i^-1 (b_i - sum_{j != i} A_ij x_j), the blocks in T and
/// the vectors and sums in X (X = double, T = float: only the matrix stored in single precision).
template <class T, class X>
inline void relax_row(const BlocksIn<T>& m, int i, const X* b, X* x) {
  const BrcMatrix& a = *m.a;
  X s[3] = {b[3 * i], b[3 * i + 1], b[3 * i + 2]};
  for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
    if (k == m.diagonal[i]) continue;
    const T* v = m.values.data() + 9 * static_cast<std::ptrdiff_t>(k);
    const X* xj = x + 3 * a.col_index[k];
    for (int r = 0; r < 3; ++r)
      s[r] -= X(v[3 * r]) * xj[0] + X(v[3 * r + 1]) * xj[1] + X(v[3 * r + 2]) * xj[2];
  }
  const T* d = m.inverse_diagonal.data() + 9 * static_cast<std::ptrdiff_t>(i);
  for (int r = 0; r < 3; ++r)
    x[3 * i + r] = X(d[3 * r]) * s[0] + X(d[3 * r + 1]) * s[1] + X(d[3 * r + 2]) * s[2];
}

/// A forward and a backward sweep (the smoothing of V(1,1)), one thread, natural order.
template <class T, class X>
inline void symmetric_sweeps(const BlocksIn<T>& m, const X* b, X* x) {
  const int n = m.a->block_rows;
  for (int i = 0; i < n; ++i) relax_row(m, i, b, x);
  for (int i = n - 1; i >= 0; --i) relax_row(m, i, b, x);
}

}  // namespace corofem::bench
