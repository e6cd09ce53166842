#pragma once
// One entry per hostile-input reader, shared by the libFuzzer targets (clang, -fsanitize=fuzzer)
// and the corpus replay gate of the normal test suite. Each feeds the bytes to the reader and
// accepts a result or an InputError; anything else (a crash, another exception, a hang caught by
// the fuzzer's timeout) is a finding.
#include <cstddef>
#include <cstdint>

namespace corofem::fuzz {

/// Scene JSON text -> parse_scene (paths resolve against a folder with no files).
void scene_input(const std::uint8_t* data, std::size_t size);
/// Bytes as a .msh file -> read_volume_mesh.
void msh_input(const std::uint8_t* data, std::size_t size);
/// Bytes as an .stl file -> tetrahedralize_surface at a coarse size.
void stl_input(const std::uint8_t* data, std::size_t size);

}  // namespace corofem::fuzz
