#pragma once
// petsc-mg's coarse operators, included only where COROFEM_HAVE_PETSC is defined. The first
// coarse level is the sum over ranks of each rank's Galerkin share of its own fine rows
// (multigrid/galerkin_row_share.hpp), added by PETSc into a distributed matrix; the coarser ones
// are MatPtAP of the level above (small). PETSc's own Galerkin (PCMG with MatPtAP on the finest
// level) kept A P of each rank's rows for reuse: 120 MB a rank at two ranks of a 415k-tet bar
// against 18 MB on one rank, which held a rank's peak memory at two ranks to 0.70 of one rank's.
#include <petscmat.h>

#include <vector>

#include "multigrid/galerkin_row_share.hpp"
#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem::petsc {

class CoarseOperators {
 public:
  /// `a`: the fine matrix's pattern as this rank holds it, its rows [begin, end) this rank's
  /// (complete); `finest`: P's rows of every vertex `a` numbers (GalerkinRowShare);
  /// `prolongations`: PETSc's P of each level, finest first (references taken), whose coarse
  /// layout the coarse operators share.
  CoarseOperators(const BrcMatrix& a, const Transfer& finest, int begin, int end,
                  const std::vector<Mat>& prolongations, MPI_Comm comm);
  ~CoarseOperators();
  CoarseOperators(const CoarseOperators&) = delete;
  CoarseOperators& operator=(const CoarseOperators&) = delete;

  /// Every coarse operator's values from `a` (of the pattern given); the first call makes the
  /// levels below the first.
  void update(const BrcMatrix& a);
  /// Level h = 1, 2, ... below the finest (ours: finest first).
  Mat level(int h) const { return levels_[h - 1]; }
  int coarse_levels() const { return static_cast<int>(levels_.size()); }

 private:
  /// The share's blocks added into `m` (ADD_VALUES; m assembled by the caller).
  void add_share_to(Mat m);
  GalerkinRowShare share_;
  std::vector<Mat> prolongations_, levels_;
  std::vector<PetscInt> columns_;  ///< scratch: one coarse row's global block columns
  std::vector<PetscScalar> row_;   ///< scratch: its 3 scalar rows, as MatSetValuesBlocked reads
};

}  // namespace corofem::petsc
