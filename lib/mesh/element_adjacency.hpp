#pragma once
// Element 1-rings: for every element, the elements sharing at least one vertex with it (itself
// included), as compressed rows.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct ElementRings {
  std::vector<int> start;     ///< #T + 1 offsets
  std::vector<int> elements;  ///< sorted neighbours of each element
};

ElementRings element_one_rings(const TetMesh& mesh);

}  // namespace corofem
