#pragma once
// PETSc's Galerkin product, the one a PETSc user would call: E_{h+1} = P_h^T E_h P_h
// by MatPtAP on AIJ matrices of block size 3, level after level, P_h = R_h^T. The first update
// runs MatPtAP's symbolic and numeric phases (MAT_INITIAL_MATRIX); every later one only the
// numeric phase on the stored patterns (MAT_REUSE_MATRIX), the mode that competes with our stream.
// Each update copies A's values into PETSc's matrix first, as any user of PETSc would have to.
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

class PetscPtapHierarchy {
 public:
  /// Throws InputError when this build has no PETSc.
  PetscPtapHierarchy(const BrcMatrix& fine_pattern, const std::vector<Transfer>& transfers);
  ~PetscPtapHierarchy();
  /// Every coarse level from A (A's pattern must be fine_pattern's).
  void update(const BrcMatrix& a);
  int num_levels() const;
  /// Level h's matrix as computed by PETSc (h = 0: A as copied in).
  Eigen::SparseMatrix<double> level(int h) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace corofem
