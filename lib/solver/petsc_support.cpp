#include "solver/petsc_support.hpp"

#include <string>

#include "core/errors.hpp"

namespace corofem::petsc {

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw NumericalFault(std::string("PETSc: ") + what + " failed (error " + std::to_string(code) + ")");
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

/// A SeqAIJ matrix from CSR arrays (copied by PETSc), block size `bs`.
Mat aij_from_csr(PetscInt rows, PetscInt cols, const std::vector<PetscInt>& row_start,
                 const std::vector<PetscInt>& columns, const PetscScalar* values, PetscInt bs) {
  Mat m = nullptr;
  check(MatCreate(PETSC_COMM_SELF, &m), "MatCreate");
  check(MatSetSizes(m, rows, cols, rows, cols), "MatSetSizes");
  check(MatSetType(m, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(m, bs), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocationCSR(m, row_start.data(), columns.data(), values), "MatSeqAIJSetPreallocationCSR");
  return m;
}

}  // namespace

void ensure_session() { static Session session; }

AijFromBrc::AijFromBrc(const BrcMatrix& a) {
  ensure_session();
  std::vector<PetscInt> row_start(1, 0), columns;
  for (int i = 0; i < a.block_rows; ++i)
    for (int r = 0; r < 3; ++r) {
      for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
        for (int c = 0; c < 3; ++c) {
          columns.push_back(3 * a.col_index[k] + c);
          scatter_.push_back(9 * static_cast<std::size_t>(k) + 3 * r + c);
        }
      row_start.push_back(static_cast<PetscInt>(columns.size()));
    }
  mat_ = aij_from_csr(3 * a.block_rows, 3 * a.block_cols, row_start, columns, nullptr, 3);
}

AijFromBrc::~AijFromBrc() {
  if (mat_) MatDestroy(&mat_);
}

void AijFromBrc::copy(const BrcMatrix& a) {
  PetscScalar* values = nullptr;
  check(MatSeqAIJGetArray(mat_, &values), "MatSeqAIJGetArray");
  for (std::size_t i = 0; i < scatter_.size(); ++i) values[i] = a.values[scatter_[i]];
  check(MatSeqAIJRestoreArray(mat_, &values), "MatSeqAIJRestoreArray");
}

Mat prolongation(const Transfer& t) {
  ensure_session();
  std::vector<PetscInt> row_start(1, 0), columns;
  std::vector<PetscScalar> values;
  for (int l = 0; l < t.fine; ++l)
    for (int c = 0; c < 3; ++c) {
      for (int k = t.p_start[l]; k < t.p_start[l + 1]; ++k) {
        columns.push_back(3 * t.p_col[k] + c);
        values.push_back(t.p_weight[k]);
      }
      row_start.push_back(static_cast<PetscInt>(columns.size()));
    }
  return aij_from_csr(3 * t.fine, 3 * t.coarse, row_start, columns, values.data(), 3);
}

}  // namespace corofem::petsc
