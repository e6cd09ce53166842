#include "solver/petsc_support.hpp"

#include <algorithm>
#include <string>
#include <type_traits>
#include <utility>

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

/// block3_matrix with its pattern from the (global) coordinates i, j of its entries; values come
/// later, in the same order, through MatSetValuesCOO (the transfers: small, set once).
Mat aij_from_coo(MPI_Comm comm, const OwnedBlocks& rows, const OwnedBlocks& cols,
                 std::vector<PetscInt> i, std::vector<PetscInt> j) {
  Mat m = block3_matrix(comm, rows, cols);
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

Mat block3_matrix(MPI_Comm comm, const OwnedBlocks& rows, const OwnedBlocks& cols, MatType type) {
  Mat m = nullptr;
  check(MatCreate(comm, &m), "MatCreate");
  check(MatSetSizes(m, 3 * rows.size(), 3 * cols.size(), 3 * rows.count, 3 * cols.count),
        "MatSetSizes");
  check(MatSetType(m, type), "MatSetType");
  check(MatSetBlockSize(m, 3), "MatSetBlockSize");
  return m;
}

AijFromBrc::AijFromBrc(const BrcMatrix& a, MPI_Comm comm, const RankPart* part) {
  ensure_session();
  const PetscInt vertices = part ? part->global_vertices : a.block_rows;
  rows_ = part
              ? OwnedBlocks{part->first_vertex, part->first_vertex + part->owned_vertices, vertices}
              : owned_blocks(vertices, comm);
  first_row_ = part ? 0 : static_cast<int>(rows_.begin);  // a part's owned rows come first
  const auto global_column = [&](int c) -> PetscInt { return part ? part->global_vertex[c] : c; };
  // PETSc's rows (3 per owned vertex) in CSR with global columns, ascending in each row: a
  // part's halo is numbered in ascending global order after its owned vertices, so each BRC
  // row's blocks are in the order PETSc's diagonal and off-diagonal parts keep them.
  in_diagonal_.resize(a.num_blocks());
  std::vector<PetscInt> row_start = {0}, columns;
  for (PetscInt b = first_row_; b < first_row_ + rows_.size(); ++b) {
    std::vector<PetscInt> row;
    for (int k = a.row_start[b]; k < a.row_start[b + 1]; ++k) {
      const PetscInt g = global_column(a.col_index[k]);
      in_diagonal_[k] = g >= rows_.begin && g < rows_.end;
      for (int c = 0; c < 3; ++c) row.push_back(3 * g + c);
    }
    std::sort(row.begin(), row.end());
    for (int r = 0; r < 3; ++r) {
      columns.insert(columns.end(), row.begin(), row.end());
      row_start.push_back(static_cast<PetscInt>(columns.size()));
    }
  }
  mat_ = block3_matrix(comm, rows_, rows_);
  // Zeros at every entry of the pattern (PETSc keeps them): the pattern is exactly the BRC's.
  check(MatSeqAIJSetPreallocationCSR(mat_, row_start.data(), columns.data(), nullptr),
        "MatSeqAIJSetPreallocationCSR");
  check(MatMPIAIJSetPreallocationCSR(mat_, row_start.data(), columns.data(), nullptr),
        "MatMPIAIJSetPreallocationCSR");
  check_layout(a);
}

/// The diagonal and off-diagonal parts of an MPIAIJ matrix; the matrix itself and none for a
/// SeqAIJ one.
std::pair<Mat, Mat> AijFromBrc::parts() const {
  MatType type = nullptr;
  check(MatGetType(mat_, &type), "MatGetType");
  if (std::string(type) == MATSEQAIJ) return {mat_, nullptr};
  Mat diagonal = nullptr, off_diagonal = nullptr;
  const PetscInt* garray = nullptr;
  check(MatMPIAIJGetSeqAIJ(mat_, &diagonal, &off_diagonal, &garray), "MatMPIAIJGetSeqAIJ");
  return {diagonal, off_diagonal};
}

void AijFromBrc::check_layout(const BrcMatrix& a) const {
  // copy() writes PETSc's value arrays directly, in the BRC's order: the row lengths of both
  // parts must be the BRC rows' diagonal and off-diagonal blocks, 3 entries each.
  const auto [diagonal, off_diagonal] = parts();
  const auto row_lengths = [](Mat m, std::vector<PetscInt>& lengths) {
    PetscInt n = 0;
    const PetscInt *ia = nullptr, *ja = nullptr;
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatGetRowIJ");
    if (!done) throw NumericalFault("PETSc: MatGetRowIJ gave no rows");
    for (PetscInt r = 0; r < n; ++r) lengths.push_back(ia[r + 1] - ia[r]);
    check(MatRestoreRowIJ(m, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatRestoreRowIJ");
  };
  std::vector<PetscInt> in_part, off_part;
  row_lengths(diagonal, in_part);
  if (off_diagonal) row_lengths(off_diagonal, off_part);
  bool same = in_part.size() == static_cast<std::size_t>(3 * rows_.size()) &&
              (!off_diagonal || off_part.size() == in_part.size());
  for (PetscInt b = 0; same && b < rows_.size(); ++b) {
    int inside = 0, total = a.row_start[first_row_ + b + 1] - a.row_start[first_row_ + b];
    for (int k = a.row_start[first_row_ + b]; k < a.row_start[first_row_ + b + 1]; ++k)
      inside += in_diagonal_[k];
    for (int r = 0; r < 3; ++r) {
      same = same && in_part[3 * b + r] == 3 * inside &&
             (off_diagonal ? off_part[3 * b + r] : 0) == 3 * (total - inside);
    }
  }
  if (!same)
    throw NumericalFault("PETSc: the AIJ matrix's rows are not the BRC pattern's it was made of");
}

AijFromBrc::~AijFromBrc() {
  if (mat_) MatDestroy(&mat_);
}

// copy() hands PETSc the BRC's doubles as its scalars.
static_assert(std::is_same_v<PetscScalar, double>, "corofem needs PETSc built with real doubles");

void AijFromBrc::copy(const BrcMatrix& a) {
  if (a.num_blocks() != static_cast<int>(in_diagonal_.size()))
    throw NumericalFault(
        "PETSc: the matrix copied is not of the pattern the AIJ matrix was made of");
  // Row r of block row b: the r-th rows of its blocks, in order, each block's into the part
  // (diagonal or off-diagonal) its column falls in; straight into PETSc's value arrays.
  const auto [diagonal, off_diagonal] = parts();
  PetscScalar *in = nullptr, *off = nullptr;
  check(MatSeqAIJGetArrayWrite(diagonal, &in), "MatSeqAIJGetArrayWrite");
  if (off_diagonal) check(MatSeqAIJGetArrayWrite(off_diagonal, &off), "MatSeqAIJGetArrayWrite");
  for (PetscInt b = first_row_; b < first_row_ + rows_.size(); ++b)
    for (int r = 0; r < 3; ++r)
      for (int k = a.row_start[b]; k < a.row_start[b + 1]; ++k) {
        const double* v = a.values.data() + 9 * static_cast<std::size_t>(k) + 3 * r;
        PetscScalar*& to = in_diagonal_[k] ? in : off;
        to[0] = v[0];
        to[1] = v[1];
        to[2] = v[2];
        to += 3;
      }
  check(MatSeqAIJRestoreArrayWrite(diagonal, &in), "MatSeqAIJRestoreArrayWrite");
  if (off_diagonal)
    check(MatSeqAIJRestoreArrayWrite(off_diagonal, &off), "MatSeqAIJRestoreArrayWrite");
  // The matrix's own state moves on, so that PETSc's preconditioners see new values.
  check(MatAssemblyBegin(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
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
