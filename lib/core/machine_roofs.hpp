#pragma once
// The two roofs of a roofline, measured on this machine: memory bandwidth as STREAM measures it
// (the triad a = b + s c on arrays far larger than any cache, 24 bytes per element: two reads,
// one write, the write's allocate read not counted, as in STREAM), and the arithmetic rate of
// a dense matrix product (Eigen's blocked, vectorized GEMM: as close to the core's peak as
// compiled code here gets). Both at thread_count() threads: the triad split across them, one
// product per thread at once.
#include <cstddef>

namespace corofem {

/// One triad pass a[i] = b[i] + s c[i], i < n, on thread_count() threads.
void stream_triad(double* a, const double* b, const double* c, double s, std::size_t n);

/// Median over `repetitions` passes on 3 arrays of `elements` doubles, in GB/s (1e9 bytes).
double measure_stream_triad_gbps(int repetitions = 7, std::size_t elements = std::size_t{1} << 24);

/// Median over `repetitions` products of two n x n matrices (2 n^3 flops each), in Gflop/s.
double measure_dense_gflops(int repetitions = 5, int n = 384);

}  // namespace corofem
