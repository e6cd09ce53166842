#include "solver/vertex_partition.hpp"

#include <algorithm>

#include "core/errors.hpp"

#ifdef COROFEM_HAVE_PETSC
#include <petscmat.h>

#include "solver/petsc_support.hpp"
#endif

namespace corofem {

#ifndef COROFEM_HAVE_PETSC

std::vector<int> partition_vertices(const TetMesh&, int) {
  return {};
}

#else

namespace {

using petsc::check;

/// PT-Scotch's partition of the vertex graph on this process alone.
std::vector<int> scotch_partition(const TetMesh& mesh, int parts) {
  const int n = mesh.num_vertices();
  std::vector<std::vector<int> > neighbours(n);
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) neighbours[t[a]].push_back(t[b]);
  // MatCreateMPIAdj takes ownership of arrays from PetscMalloc: the graph without self-loops.
  PetscInt *ia = nullptr, *ja = nullptr;
  std::size_t edges = 0;
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    edges += list.size();
  }
  check(PetscMalloc1(n + 1, &ia), "PetscMalloc1");
  check(PetscMalloc1(edges, &ja), "PetscMalloc1");
  ia[0] = 0;
  for (int v = 0; v < n; ++v) {
    std::copy(neighbours[v].begin(), neighbours[v].end(), ja + ia[v]);
    ia[v + 1] = ia[v] + static_cast<PetscInt>(neighbours[v].size());
  }
  neighbours = {};
  Mat adjacency = nullptr;
  check(MatCreateMPIAdj(PETSC_COMM_SELF, n, n, ia, ja, nullptr, &adjacency), "MatCreateMPIAdj");
  MatPartitioning partitioning = nullptr;
  IS owner = nullptr;
  std::vector<int> part;
  const PetscErrorCode status = [&] {
    PetscCall(MatPartitioningCreate(PETSC_COMM_SELF, &partitioning));
    PetscCall(MatPartitioningSetAdjacency(partitioning, adjacency));
    PetscCall(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH));
    PetscCall(MatPartitioningSetNParts(partitioning, parts));
    PetscCall(MatPartitioningApply(partitioning, &owner));
    const PetscInt* index = nullptr;
    PetscCall(ISGetIndices(owner, &index));
    part.assign(index, index + n);
    PetscCall(ISRestoreIndices(owner, &index));
    return PetscErrorCode(0);
  }();
  if (owner) ISDestroy(&owner);
  if (partitioning) MatPartitioningDestroy(&partitioning);
  MatDestroy(&adjacency);
  check(status, "MatPartitioning (PT-Scotch)");
  return part;
}

}  // namespace

std::vector<int> partition_vertices(const TetMesh& mesh, int parts) {
  petsc::ensure_session();
  std::vector<int> part = scotch_partition(mesh, parts);
  std::vector<int> sizes(parts, 0);
  for (int p : part) {
    if (p < 0 || p >= parts) return {};
    ++sizes[p];
  }
  if (std::count(sizes.begin(), sizes.end(), 0) > 0) return {};
  return part;
}

#endif

}  // namespace corofem
