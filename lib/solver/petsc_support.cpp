#include "solver/petsc_support.hpp"

#include <string>
#include <type_traits>

#include "core/errors.hpp"

namespace corofem::petsc {

void check(PetscErrorCode code, const char* what) {
  if (code != 0)
    throw NumericalFault(std::string("PETSc: ") + what + " failed (error " + std::to_string(code) +
                         ")");
}

namespace {

class Session {
 public:
  Session() {
    // PETSc's signal handler would turn every crash or interrupt of the whole program into an
    // MPI_Abort; corofem keeps its own.
    check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
    check(PetscInitializeNoArguments(), "PetscInitialize");
    check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
  }
  ~Session() { PetscFinalize(); }
};

/// An AIJ matrix of block size 3 on `comm` with this rank's rows of `rows` and columns split as
/// `cols`, its pattern from the (global) coordinates i, j of its entries; values come later, in
/// the same order, through MatSetValuesCOO (one path for one rank and for many).
Mat aij_from_coo(MPI_Comm comm, const OwnedBlocks& rows, const OwnedBlocks& cols,
                 std::vector<PetscInt> i, std::vector<PetscInt> j) {
  Mat m = nullptr;
  check(MatCreate(comm, &m), "MatCreate");
  check(MatSetSizes(m, 3 * rows.size(), 3 * cols.size(), 3 * rows.count, 3 * cols.count),
        "MatSetSizes");
  check(MatSetType(m, MATAIJ), "MatSetType");
  check(MatSetBlockSize(m, 3), "MatSetBlockSize");
  check(MatSetPreallocationCOO(m, static_cast<PetscCount>(i.size()), i.data(), j.data()),
        "MatSetPreallocationCOO");
  return m;
}

}  // namespace

void ensure_session() {
  static Session session;
}

PetscInt share_start(PetscInt count, int rank, int size) {
  return rank_share_start(static_cast<int>(count), rank, size);
}

OwnedBlocks owned_blocks(PetscInt count, MPI_Comm comm) {
  PetscMPIInt rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  return {share_start(count, rank, size), share_start(count, rank + 1, size), count};
}

AijFromBrc::AijFromBrc(const BrcMatrix& a, MPI_Comm comm, const RankPart* part) {
  ensure_session();
  const PetscInt vertices = part ? part->global_vertices : a.block_rows;
  rows_ = part
              ? OwnedBlocks{part->first_vertex, part->first_vertex + part->owned_vertices, vertices}
              : owned_blocks(vertices, comm);
  const PetscInt first_local = part ? 0 : rows_.begin;  // a part's owned rows come first
  const auto global_column = [&](int c) { return part ? part->global_vertex[c] : c; };
  // The COO entries in the BRC's own storage order (block by block, each row-major), so that
  // this rank's values are one contiguous slice of the BRC's: no copy, no scatter.
  first_value_ = 9 * static_cast<std::size_t>(a.row_start[first_local]);
  value_count_ =
      9 * static_cast<std::size_t>(a.row_start[first_local + rows_.size()]) - first_value_;
  std::vector<PetscInt> i, j;
  i.reserve(value_count_);
  j.reserve(value_count_);
  for (PetscInt g = rows_.begin; g < rows_.end; ++g) {
    const PetscInt b = g - rows_.begin + first_local;
    for (int k = a.row_start[b]; k < a.row_start[b + 1]; ++k) {
      const PetscInt column = 3 * static_cast<PetscInt>(global_column(a.col_index[k]));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          i.push_back(3 * g + r);
          j.push_back(column + c);
        }
    }
  }
  mat_ = aij_from_coo(comm, rows_, rows_, std::move(i), std::move(j));
}

AijFromBrc::~AijFromBrc() {
  if (mat_) MatDestroy(&mat_);
}

// copy() hands PETSc the BRC's doubles as its scalars.
static_assert(std::is_same_v<PetscScalar, double>, "corofem needs PETSc built with real doubles");

void AijFromBrc::copy(const BrcMatrix& a) {
  if (a.values.size() < first_value_ + value_count_)
    throw NumericalFault(
        "PETSc: the matrix copied is not of the pattern the AIJ matrix was made of");
  check(MatSetValuesCOO(mat_, a.values.data() + first_value_, INSERT_VALUES), "MatSetValuesCOO");
}

Mat prolongation(const Transfer& t, MPI_Comm comm, const OwnedBlocks* fine_rows) {
  ensure_session();
  const OwnedBlocks rows = fine_rows ? *fine_rows : owned_blocks(t.fine, comm);
  if (rows.begin < t.first_row ||
      rows.end - t.first_row + 1 > static_cast<PetscInt>(t.p_start.size()))
    throw NumericalFault("PETSc: a transfer lacks rows of this rank's fine vertices");
  std::vector<PetscInt> i, j;
  std::vector<PetscScalar> values;
  for (PetscInt l = rows.begin; l < rows.end; ++l)
    for (int c = 0; c < 3; ++c)
      for (int k = t.p_start[l - t.first_row]; k < t.p_start[l - t.first_row + 1]; ++k) {
        i.push_back(3 * l + c);
        j.push_back(3 * t.p_col[k] + c);
        values.push_back(t.p_weight[k]);
      }
  Mat p = aij_from_coo(comm, rows, owned_blocks(t.coarse, comm), std::move(i), std::move(j));
  check(MatSetValuesCOO(p, values.data(), INSERT_VALUES), "MatSetValuesCOO");
  return p;
}

}  // namespace corofem::petsc
