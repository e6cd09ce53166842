#pragma once
// PETSc plumbing shared by the PETSc solvers and the MatPtAP comparison; included only where
// COROFEM_HAVE_PETSC is defined.
#include <petscmat.h>

#include <cstddef>
#include <vector>

#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem::petsc {

/// Throws NumericalFault naming `what` when PETSc returned an error code.
void check(PetscErrorCode code, const char* what);

/// PETSc (and MPI, unless the program started it) initialized once, finalized at exit. Errors
/// come back as codes, not as messages printed by PETSc.
void ensure_session();

/// A SeqAIJ matrix of block size 3 with a BRC matrix's pattern (scalar row 3i + r, columns in
/// the blocks' order), built once; copy() moves new BRC values in through the stored scatter.
class AijFromBrc {
 public:
  explicit AijFromBrc(const BrcMatrix& pattern);
  ~AijFromBrc();
  AijFromBrc(const AijFromBrc&) = delete;
  AijFromBrc& operator=(const AijFromBrc&) = delete;
  void copy(const BrcMatrix& a);
  Mat mat() const { return mat_; }

 private:
  Mat mat_ = nullptr;
  std::vector<std::size_t> scatter_;  ///< AIJ value i = BRC value scatter_[i]
};

/// P = R^T as a SeqAIJ matrix (3 fine x 3 coarse, R = Rs (x) I3). The caller destroys it.
Mat prolongation(const Transfer& t);

}  // namespace corofem::petsc
