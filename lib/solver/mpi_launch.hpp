#pragma once
// `mpirun -np N corofem run SCENE.json`: every rank builds the scene and assembles the whole
// system (replicated, not distributed), the PETSc and hypre solvers distribute the solve over the
// ranks (each owns a contiguous share of the vertices), every rank gets the whole solution back,
// and rank 0 alone writes files and progress. Without mpirun there is one rank and no MPI call.
namespace corofem {

struct MpiLaunch {
  int rank = 0;
  int size = 1;
  int ranks_on_this_machine = 1;  ///< to share the cores: threads per rank = cores / this
};

/// The ranks this process was launched among, read from the launcher's environment (Open MPI's
/// OMPI_COMM_WORLD_SIZE, MPICH's PMI_SIZE) and then from MPI itself. Throws InputError when
/// launched on several ranks by a build without PETSc (and so without MPI).
MpiLaunch mpi_launch();

/// Ends every rank with `code` when this is one of several: a rank that stops on an error must
/// not leave the others waiting in a collective call. Returns when there is one rank.
void abort_all_ranks(int code);

}  // namespace corofem
