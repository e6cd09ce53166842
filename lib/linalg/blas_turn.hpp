#pragma once
// The libraries that call BLAS (CHOLMOD's supernodal factorization, UMFPACK) take turns across
// threads: Debian's serial OpenBLAS (0.3.21, the default libblas.so.3 alternative) keeps its work
// buffers unlocked, so two factorizations in threads side by side (the stability study's runs)
// corrupted each other's results at round-off and beyond (same runs, different bits; with the
// reference BLAS they agree). Our own kernels call no BLAS and never wait here.
#include <mutex>

namespace corofem {

/// Held for the duration of one BLAS-using library call.
std::unique_lock<std::mutex> take_blas_turn();

}  // namespace corofem
