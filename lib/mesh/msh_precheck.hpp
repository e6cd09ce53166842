#pragma once
// Checks .msh and .stl files before gmsh sees them. gmsh 4.8 trusts the counts and tag ranges in
// section headers and allocates from them, matches section names by prefix, and keeps null
// vertices for undefined node references (fuzzing found a 2.9e18-byte request, a heap corruption
// and a segfault); so ASCII files are checked structurally here, binary ones by check_binary_msh.
#include <filesystem>
#include <string>

namespace corofem {

/// Throws InputError naming the file and the section when: the file does not start with a
/// $MeshFormat section; the version is not 2.x or 4.x or the data size not 8; a binary file fails
/// check_binary_msh; in an ASCII file, a count in $Entities, $Nodes, $Elements or $PhysicalNames
/// exceeds the file's size in bytes (every item takes at least one byte); or a node or element tag
/// range exceeds 1e9 or has min > max; an unknown section header (gmsh matches names by prefix); a
/// malformed $Nodes or $Elements body; or an element referring to a node $Nodes does not define.
void precheck_msh(const std::filesystem::path& file);

/// One line of a $PhysicalNames body (ASCII in binary files too): `dim tag "name"` with dim in
/// 0..3 and tag > 0, else InputError naming the file (gmsh 4.8 crashes on a dimension of 7).
void check_physical_name_line(const std::string& line, const std::filesystem::path& file);

/// An STL that does not start with "solid" is binary: its 32-bit triangle count at byte 80 must
/// account for the file's size exactly (84 + 50 n bytes), or InputError names the file.
void precheck_stl(const std::filesystem::path& file);

}  // namespace corofem
