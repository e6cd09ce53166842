#pragma once
// Provenance of this binary; the definitions are generated at build time
// (cmake/write_build_info.cmake).

namespace corofem {
const char* build_commit();
const char* build_compiler();
const char* build_flags();
const char* build_type();
}  // namespace corofem
