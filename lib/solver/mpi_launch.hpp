#pragma once
// `mpirun -np N corofem run SCENE.json`: the PETSc and hypre solvers distribute the solve over the
// ranks (each owns a contiguous share of the vertices); a dynamic linearly implicit or a static
// lagged run distributes the mesh and the element work too (scene/scene_simulation.hpp). Rank 0
// alone writes RESULT.json and the progress.
// Without mpirun there is one rank and no MPI call.
#include <string>
#include <vector>

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

/// The number of ranks the launcher's environment announces (1 without a launcher); no MPI call.
int launcher_size();

/// This process's rank as the launcher's environment gives it (0 without a launcher); no MPI
/// call, so it can be asked at any time, even where MPI failed to start.
int launcher_rank();

/// Ends every rank with `code` when this is one of several: a rank that stops on an error must
/// not leave the others waiting in a collective call. Returns when there is one rank.
void abort_all_ranks(int code);

/// The sum of `value` over the ranks (on every rank); `value` itself with one rank.
double sum_over_ranks(double value);

/// The largest `value` over the ranks (on every rank); `value` itself with one rank.
double max_over_ranks(double value);

/// Rank 0's `status` and `message` on every rank (a collective call; unchanged with one rank):
/// how rank 0, alone doing work that can fail, tells the others whether it did.
void broadcast_status(int& status, std::string& message);

/// Point to point, for what one rank hands another (any size: sent in pieces under MPI's int
/// counts). The receiver calls receive_bytes(from) for every send_bytes(to, ...).
void send_bytes(int to, const std::vector<char>& bytes);
std::vector<char> receive_bytes(int from);

/// Every rank's `mine`, concatenated in rank order, on rank 0; empty on the others; `mine`
/// itself with one rank.
std::vector<double> gather_on_rank0(const std::vector<double>& mine);

}  // namespace corofem
