#pragma once
// Linear tetrahedral mesh with the tags it was read with.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace corofem {

using Tet = std::array<int, 4>;

struct TetMesh {
  std::vector<Vec3> rest;                 ///< #V rest positions
  std::vector<Tet> tets;                  ///< #T vertex indices, positively oriented
  std::vector<std::size_t> node_tags;     ///< #V tags of the input (1-based for generated meshes)
  std::vector<std::size_t> element_tags;  ///< #T tags of the input
  std::string source;                     ///< file name or "box" (for messages)

  int num_vertices() const { return static_cast<int>(rest.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
};

/// Signed volume of the tet (a, b, c, d): positive when (b-a, c-a, d-a) is right-handed.
double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// What validate_mesh changed.
struct MeshValidation {
  int reoriented = 0;      ///< inverted rest tets made positive by swapping two vertices
  int unused_removed = 0;  ///< vertices that no tet uses, dropped
};

/// Checks a mesh and puts it in canonical form. Throws InputError (naming `mesh.source` and the
/// node or element tag) for: no tets, out-of-range indices, non-finite coordinates, degenerate tets
/// (|V| < 1e-8 * longest edge^3; a regular tet has V = 0.118 L^3). Inverted rest tets are
/// reoriented (vertices 2 and 3 swapped), not rejected: a negative orientation in a file is a
/// convention, not a defect. Vertices used by no tet are removed (they would make K singular).
MeshValidation validate_mesh(TetMesh& mesh);

/// Axis-aligned bounding box of the rest positions: {min, max}.
std::array<Vec3, 2> bounding_box(const std::vector<Vec3>& points);

}  // namespace corofem
