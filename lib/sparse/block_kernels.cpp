#include "sparse/block_kernels.hpp"

namespace corofem {
namespace {

bool cpu_has_avx2_fma() {
#ifdef COROFEM_HAVE_AVX2_KERNELS
  __builtin_cpu_init();  // needed before main (this runs in a static initializer)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

const bool cpu_has_vector_kernels = cpu_has_avx2_fma();

}  // namespace

namespace detail {
bool vector_block_kernels_on = cpu_has_vector_kernels;
}

bool set_vector_block_kernels(bool on) {
  const bool previous = detail::vector_block_kernels_on;
  detail::vector_block_kernels_on = on && cpu_has_vector_kernels;
  return previous;
}

const char* block_kernels_name() {
  return vector_block_kernels() ? "avx2-fma" : "scalar";
}

}  // namespace corofem
