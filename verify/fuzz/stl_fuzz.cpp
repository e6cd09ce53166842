// libFuzzer target: stl reader (see fuzz_entries.hpp).
#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  corofem::fuzz::stl_input(data, size);
  return 0;
}
