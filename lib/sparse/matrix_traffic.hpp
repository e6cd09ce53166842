#pragma once
// Compulsory traffic of a pass over a BRC matrix: the bytes a kernel must move and the flops it
// must do, counted from the sizes of what it touches (the roofline's unit, report/step_roofline).
// Here so that each kernel's owner (a smoother, say) can count its own.
#include <cmath>

#include "sparse/brc_matrix.hpp"

namespace corofem {

struct Traffic {
  double bytes = 0;
  double flops = 0;
  Traffic& operator+=(const Traffic& o) {
    bytes += o.bytes;
    flops += o.flops;
    return *this;
  }
};
inline Traffic operator*(double k, Traffic t) {
  return {k * t.bytes, k * t.flops};
}

inline constexpr double kCacheLine = 64;   // bytes per cache line
inline constexpr double kBlockBytes = 72;  // a 3x3 block of doubles
inline constexpr double kIndexBytes = 4;   // int

/// Cache lines spanned by a member of `bytes` read out of a larger struct.
inline double cache_lines(double bytes) {
  return std::ceil(bytes / kCacheLine) * kCacheLine;
}

/// BRC storage of a matrix: values, column indices, row starts.
inline double matrix_bytes(const BrcMatrix& a) {
  const double blocks = static_cast<double>(a.col_index.size());
  return (kBlockBytes + kIndexBytes) * blocks + kIndexBytes * (a.block_rows + 1);
}

/// y = A x.
inline Traffic matvec_traffic(const BrcMatrix& a) {
  const double n = 3.0 * a.block_rows;
  return {matrix_bytes(a) + 16 * n, 18.0 * static_cast<double>(a.col_index.size())};
}

/// Blocks left of the diagonal (what a sweep from x = 0 reads).
inline double blocks_below_diagonal(const BrcMatrix& a) {
  double lower = 0;
  for (int i = 0; i < a.block_rows; ++i)
    for (int k = a.row_start[i]; k < a.row_start[i + 1] && a.col_index[k] < i; ++k) ++lower;
  return lower;
}

}  // namespace corofem
