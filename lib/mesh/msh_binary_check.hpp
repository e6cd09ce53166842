#pragma once
// Validates binary .msh files (v4.1 and v2.2, little-endian, 8-byte doubles) before gmsh opens
// them. gmsh's binary readers allocate from the counts in section headers, write one cache entry
// per node or element read whatever the header declared, and keep reading past a block's end; so
// every count and length is checked here against the bytes that remain, and every element's node
// references against the nodes defined. Only what this check walked end to end reaches gmsh.
#include <filesystem>
#include <string>

namespace corofem {

/// Throws InputError naming the file and the section when `bytes` (the whole file, whose
/// $MeshFormat line says binary, version `version`) is not a well-formed sequence of the sections
/// $MeshFormat, $PhysicalNames (ASCII body), $Entities (v4.1), $Nodes and $Elements. Rejected:
/// big-endian files, versions other than 4.1 and 2.2, any other section, a count that exceeds the
/// bytes left, node or element tags outside their declared range (or above 1e9, or 0) or defined
/// twice, block totals that differ from the header, element types without a known node count, an
/// element referring to an undefined node, and anything between or after sections.
void check_binary_msh(const std::string& bytes, double version, const std::filesystem::path& file);

}  // namespace corofem
