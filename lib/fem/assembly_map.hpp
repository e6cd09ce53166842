#pragma once
// The vertex-pair pattern of a tet mesh and, for every (element, vertex pair), the index of its
// destination block, so that per-step assembly writes without searching (paper 4.2).
#include <array>
#include <cstdint>
#include <vector>

#include "fem/element_partition.hpp"
#include "mesh/tet_mesh.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

struct AssemblyMap {
  std::vector<std::array<int, 16>> block;  ///< block[e][4a+b] = block index of (tet[a], tet[b])
  /// Bit 4a+b of first[e]: e is the lowest-numbered element with a block for (tet[a], tet[b]).
  /// The assembly visits a block's elements in ascending order at every thread count, so the
  /// first one stores and the others add: K needs no zero fill.
  std::vector<std::uint16_t> first;
  std::vector<int> diagonal;  ///< block index of (v, v) per vertex
  RowPartition rows;          ///< rows per thread (threads_for(tets) at construction)
};

/// Zero matrix with one block per pair of vertices sharing an element, and its assembly map
/// (its row partition for the threads its size uses, threads_for(tets)).
BrcMatrix make_stiffness_pattern(const TetMesh& mesh, AssemblyMap& map);

}  // namespace corofem
