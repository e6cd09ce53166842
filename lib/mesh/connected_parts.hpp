#pragma once
// The pieces a tet mesh falls into: vertices joined through the tets they share. One STL can
// hold several bodies, and a static analysis needs each of them held.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct ConnectedParts {
  int count = 0;
  std::vector<int> of_vertex;  ///< each vertex's part, numbered 0.. in order of first vertex
};

ConnectedParts connected_parts(const TetMesh& mesh);

}  // namespace corofem
