#pragma once
// The partition of a mesh's vertices over MPI ranks for a distributed run: PETSc's
// MatPartitioning with PT-Scotch on the vertex graph (the mesh's edges), computed by the calling
// process alone (rank 0, the one that holds the whole mesh: no MPI call). Rank parts then become
// contiguous ranges of the vertex order (mesh/rank_part.hpp: group_vertices_by_part).
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

/// The part (rank) of every vertex of `mesh`, `parts` of them, balanced in vertices with few
/// edges cut. Empty when PT-Scotch left a part empty (a mesh too small for the ranks) or this
/// build has no PETSc: the caller splits the vertex order into equal shares instead.
std::vector<int> partition_vertices(const TetMesh& mesh, int parts);

}  // namespace corofem
