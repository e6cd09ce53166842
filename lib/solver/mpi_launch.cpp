#include "solver/mpi_launch.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "core/errors.hpp"

#ifdef COROFEM_HAVE_PETSC
#include "solver/petsc_support.hpp"
#endif

namespace corofem {

int launcher_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  return 1;
}

int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* value = std::getenv(name)) return std::max(0, std::atoi(value));
  return 0;
}

MpiLaunch mpi_launch() {
  static const MpiLaunch launch = [] {
    MpiLaunch l;
    const int announced = launcher_size();
    if (announced == 1) return l;
#ifndef COROFEM_HAVE_PETSC
    throw InputError(
        "launched on " + std::to_string(announced) +
        " MPI ranks, but this build of corofem has no PETSc and so no MPI (install petsc-dev, as "
        "ci/setup does, and rebuild)");
#else
    petsc::ensure_session();
    MPI_Comm_rank(PETSC_COMM_WORLD, &l.rank);
    MPI_Comm_size(PETSC_COMM_WORLD, &l.size);
    MPI_Comm local;
    MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
    MPI_Comm_size(local, &l.ranks_on_this_machine);
    MPI_Comm_free(&local);
    return l;
#endif
  }();
  return launch;
}

void abort_all_ranks(int code) {
#ifdef COROFEM_HAVE_PETSC
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (!initialized || finalized) return;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) MPI_Abort(MPI_COMM_WORLD, code);
#else
  (void)code;
#endif
}

namespace {

/// `value` over the ranks, their largest or their sum (itself with one rank).
double reduce_over_ranks(double value, [[maybe_unused]] const char* what,
                         [[maybe_unused]] bool largest) {
#ifdef COROFEM_HAVE_PETSC
  if (mpi_launch().size > 1) {
    double reduced = 0;
    if (MPI_Allreduce(&value, &reduced, 1, MPI_DOUBLE, largest ? MPI_MAX : MPI_SUM,
                      PETSC_COMM_WORLD) != MPI_SUCCESS)
      throw NumericalFault(std::string("MPI_Allreduce of a ") + what + " over the ranks failed");
    return reduced;
  }
#endif
  return value;
}

}  // namespace

double sum_over_ranks(double value) {
  return reduce_over_ranks(value, "sum", false);
}

double max_over_ranks(double value) {
  return reduce_over_ranks(value, "maximum", true);
}

namespace {
// MPI counts are ints: larger messages go in pieces of this many bytes.
constexpr std::size_t kMessagePiece = std::size_t{1} << 30;
}  // namespace

void broadcast_status(int& status, std::string& message) {
#ifdef COROFEM_HAVE_PETSC
  if (mpi_launch().size > 1) {
    unsigned long long length = message.size();
    if (MPI_Bcast(&status, 1, MPI_INT, 0, PETSC_COMM_WORLD) != MPI_SUCCESS ||
        MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, PETSC_COMM_WORLD) != MPI_SUCCESS)
      throw NumericalFault("MPI_Bcast of rank 0's status failed");
    message.resize(length);
    if (length > 0 && MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, 0,
                                PETSC_COMM_WORLD) != MPI_SUCCESS)
      throw NumericalFault("MPI_Bcast of rank 0's message failed");
  }
#else
  (void)status;
  (void)message;
#endif
}

void send_bytes(int to, const std::vector<char>& bytes) {
#ifdef COROFEM_HAVE_PETSC
  unsigned long long size = bytes.size();
  bool ok = MPI_Send(&size, 1, MPI_UNSIGNED_LONG_LONG, to, 0, PETSC_COMM_WORLD) == MPI_SUCCESS;
  for (std::size_t at = 0; ok && at < bytes.size(); at += kMessagePiece) {
    const int count = static_cast<int>(std::min(kMessagePiece, bytes.size() - at));
    ok = MPI_Send(bytes.data() + at, count, MPI_BYTE, to, 0, PETSC_COMM_WORLD) == MPI_SUCCESS;
  }
  if (!ok) throw NumericalFault("MPI_Send to rank " + std::to_string(to) + " failed");
#else
  (void)to;
  (void)bytes;
  throw NumericalFault("send_bytes: this build has no MPI");
#endif
}

std::vector<char> receive_bytes(int from) {
#ifdef COROFEM_HAVE_PETSC
  unsigned long long size = 0;
  bool ok = MPI_Recv(&size, 1, MPI_UNSIGNED_LONG_LONG, from, 0, PETSC_COMM_WORLD,
                     MPI_STATUS_IGNORE) == MPI_SUCCESS;
  std::vector<char> bytes(ok ? size : 0);
  for (std::size_t at = 0; ok && at < bytes.size(); at += kMessagePiece) {
    const int count = static_cast<int>(std::min(kMessagePiece, bytes.size() - at));
    ok = MPI_Recv(bytes.data() + at, count, MPI_BYTE, from, 0, PETSC_COMM_WORLD,
                  MPI_STATUS_IGNORE) == MPI_SUCCESS;
  }
  if (!ok) throw NumericalFault("MPI_Recv from rank " + std::to_string(from) + " failed");
  return bytes;
#else
  (void)from;
  throw NumericalFault("receive_bytes: this build has no MPI");
#endif
}

std::vector<double> gather_on_rank0(const std::vector<double>& mine) {
#ifdef COROFEM_HAVE_PETSC
  const MpiLaunch mpi = mpi_launch();
  if (mpi.size > 1) {
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(mpi.size), starts(mpi.size);
    if (MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD) !=
        MPI_SUCCESS)
      throw NumericalFault("MPI_Gather of the ranks' sizes failed");
    std::vector<double> all;
    if (mpi.rank == 0) {
      for (int r = 1; r < mpi.size; ++r) starts[r] = starts[r - 1] + counts[r - 1];
      all.resize(static_cast<std::size_t>(starts.back()) + counts.back());
    }
    if (MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(),
                    MPI_DOUBLE, 0, PETSC_COMM_WORLD) != MPI_SUCCESS)
      throw NumericalFault("MPI_Gatherv of the ranks' values failed");
    return all;
  }
#endif
  return mine;
}

}  // namespace corofem
