#pragma once
// PETSc plumbing shared by the PETSc solvers and the MatPtAP comparison; included only where
// COROFEM_HAVE_PETSC is defined. Matrices live on a communicator: PETSC_COMM_SELF for the
// one-process comparisons, PETSC_COMM_WORLD for the solvers (one rank, or the ranks of mpirun).
// Each rank owns a contiguous range of vertices, the block rows it gives PETSc: equal shares
// (rank_share_start), or a distributed mesh's part's.
// Replicated: every rank holds the whole BRC matrix. Distributed (a RankPart): each holds its
// part's matrix, its owned rows first, the columns numbered locally.
#include <petscmat.h>

#include <cstddef>
#include <vector>

#include "mesh/rank_part.hpp"
#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem::petsc {

/// Throws NumericalFault naming `what` when PETSc returned an error code.
void check(PetscErrorCode code, const char* what);

/// PETSc (and MPI, unless the program started it) initialized once, finalized at exit. Errors
/// come back as codes, not as messages printed by PETSc.
void ensure_session();

/// The vertices [begin, end) of `count` this rank owns on `comm`: equal contiguous shares.
struct OwnedBlocks {
  PetscInt begin = 0, end = 0, count = 0;
  PetscInt size() const { return end - begin; }
};
OwnedBlocks owned_blocks(PetscInt count, MPI_Comm comm);
/// The first of `count` vertices rank `rank` of `size` owns (rank = size: count).
PetscInt share_start(PetscInt count, int rank, int size);

/// A matrix of block size 3 on `comm` with this rank's rows of `rows` and columns split as
/// `cols`, before its pattern: AIJ, or `type` (MATPREALLOCATOR, to sum a pattern across ranks).
Mat block3_matrix(MPI_Comm comm, const OwnedBlocks& rows, const OwnedBlocks& cols,
                  MatType type = MATAIJ);

/// An AIJ matrix of block size 3 with a BRC matrix's pattern on `comm` (this rank's rows: its
/// owned vertices), built once from the pattern in CSR; copy() writes the BRC values of those
/// rows into PETSc's value arrays directly (no COO maps: they cost 16 bytes per entry, more
/// than the matrix, and their set-up's scratch raised the peak further on several ranks).
/// With `part`, `pattern` is the part's matrix (rows and columns in its local numbering).
class AijFromBrc {
 public:
  explicit AijFromBrc(const BrcMatrix& pattern, MPI_Comm comm = PETSC_COMM_SELF,
                      const RankPart* part = nullptr);
  ~AijFromBrc();
  AijFromBrc(const AijFromBrc&) = delete;
  AijFromBrc& operator=(const AijFromBrc&) = delete;
  void copy(const BrcMatrix& a);
  Mat mat() const { return mat_; }
  const OwnedBlocks& rows() const { return rows_; }

 private:
  std::pair<Mat, Mat> parts() const;
  void check_layout(const BrcMatrix& a) const;
  Mat mat_ = nullptr;
  OwnedBlocks rows_;
  int first_row_ = 0;              ///< the BRC's first block row that is this rank's
  std::vector<char> in_diagonal_;  ///< per BRC block: its column is owned here
};

/// P = R^T as an AIJ matrix on `comm` (3 fine x 3 coarse, R = Rs (x) I3; rows and columns owned
/// as owned_blocks splits the fine and the coarse vertices, or the rows as `fine_rows` gives them:
/// the fine matrix's). The caller destroys it.
Mat prolongation(const Transfer& t, MPI_Comm comm = PETSC_COMM_SELF,
                 const OwnedBlocks* fine_rows = nullptr);

}  // namespace corofem::petsc
