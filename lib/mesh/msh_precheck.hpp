#pragma once
// Checks .msh and .stl files before gmsh sees them. gmsh 4.8 trusts the counts and tag ranges in
// section headers and allocates from them, matches section names by prefix, and keeps null
// vertices for undefined node references (fuzzing found a 2.9e18-byte request, a heap corruption
// and a segfault); so ASCII files are checked structurally here, and binary ones are refused.
#include <filesystem>

namespace corofem {

/// Throws InputError naming the file and the section when: the file does not start with a
/// $MeshFormat section; the version is not 2.x or 4.x or the data size not 8; the file is binary
/// (its body cannot be validated without a full binary parser; the message says how to convert); a count in $Entities, $Nodes, $Elements or $PhysicalNames exceeds
/// the file's size in bytes (every item takes at least one byte); or a node or element tag range
/// exceeds 1e9 or has min > max; an unknown section header (gmsh matches names by prefix); a
/// malformed $Nodes or $Elements body; or an element referring to a node $Nodes does not define.
void precheck_msh(const std::filesystem::path& file);

/// An STL that does not start with "solid" is binary: its 32-bit triangle count at byte 80 must
/// account for the file's size exactly (84 + 50 n bytes), or InputError names the file.
void precheck_stl(const std::filesystem::path& file);

}  // namespace corofem
