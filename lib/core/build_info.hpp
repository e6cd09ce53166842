#pragma once
// Provenance of this binary; the definitions are generated at build time
// (cmake/write_build_info.cmake).

namespace corofem {
const char* build_commit();
const char* build_compiler();
const char* build_flags();
const char* build_type();
const char* build_version();  ///< the project's version (CMakeLists.txt), e.g. "0.1.0"
}  // namespace corofem
