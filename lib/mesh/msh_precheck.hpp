#pragma once
// Checks .msh and .stl files before gmsh sees them. gmsh 4.8 trusts the counts and tag ranges in section
// headers and allocates from them (a fuzzed binary v4.1 file made it request 2.9e18 bytes), so
// the counts that size its arrays are read here first, in ASCII and binary layouts.
#include <filesystem>

namespace corofem {

/// Throws InputError naming the file and the section when: the file does not start with a
/// $MeshFormat section; the version is not 2.x or 4.x, the file type not 0 (ASCII) or 1 (binary),
/// or the data size not 8; a count in $Entities, $Nodes, $Elements or $PhysicalNames exceeds
/// the file's size in bytes (every item takes at least one byte); or a node or element tag range
/// exceeds 1e9 or has min > max; in ASCII files, also an unknown section header (gmsh matches
/// names by prefix), a malformed $Nodes or $Elements body or an
/// element referring to a node $Nodes does not define. Binary bodies are not parsed here.
void precheck_msh(const std::filesystem::path& file);

/// An STL that does not start with "solid" is binary: its 32-bit triangle count at byte 80 must
/// account for the file's size exactly (84 + 50 n bytes), or InputError names the file.
void precheck_stl(const std::filesystem::path& file);

}  // namespace corofem
