#include "solver/petsc_coarse_operators.hpp"

#include "solver/petsc_support.hpp"

namespace corofem::petsc {

CoarseOperators::CoarseOperators(const BrcMatrix& a, const Transfer& finest, int begin, int end,
                                 const std::vector<Mat>& prolongations, MPI_Comm comm)
    : share_(a, finest, begin, end), prolongations_(prolongations) {
  for (Mat p : prolongations_)
    check(PetscObjectReference(reinterpret_cast<PetscObject>(p)), "PetscObjectReference");
  // The first coarse level's pattern: every rank's share, added; PETSc's preallocator sums the
  // patterns across ranks (rows owned elsewhere are sent).
  const OwnedBlocks coarse = owned_blocks(share_.share().block_rows, comm);
  Mat first = block3_matrix(comm, coarse, coarse);
  levels_.push_back(first);
  Mat pattern = block3_matrix(comm, coarse, coarse, MATPREALLOCATOR);
  check(MatSetUp(pattern), "MatSetUp");
  add_share_to(pattern);  // zeros: only the pattern counts
  check(MatAssemblyBegin(pattern, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(pattern, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatPreallocatorPreallocate(pattern, PETSC_TRUE, first), "MatPreallocatorPreallocate");
  MatDestroy(&pattern);
  // Every later update adds into exactly this pattern, and sends the same rows elsewhere.
  check(MatSetOption(first, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(first, MAT_SUBSET_OFF_PROC_ENTRIES, PETSC_TRUE), "MatSetOption");
  levels_.resize(prolongations_.size(), nullptr);
}

CoarseOperators::~CoarseOperators() {
  for (Mat& m : levels_)
    if (m) MatDestroy(&m);
  for (Mat& p : prolongations_) MatDestroy(&p);
}

void CoarseOperators::add_share_to(Mat m) {
  // One call per coarse row: its blocks' 3 scalar rows laid out row after row, as
  // MatSetValuesBlocked reads them (the BRC keeps each 3x3 block's 9 values together).
  const BrcMatrix& e = share_.share();
  for (int i = 0; i < e.block_rows; ++i) {
    const int first = e.row_start[i], count = e.row_start[i + 1] - first;
    if (count == 0) continue;  // a row none of this rank's fine rows restricts to
    columns_.assign(e.col_index.begin() + first, e.col_index.begin() + first + count);
    row_.resize(9 * static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          row_[3 * (r * count + k) + c] =
              e.values[9 * static_cast<std::size_t>(first + k) + 3 * r + c];
    const PetscInt row = i;
    check(MatSetValuesBlocked(m, 1, &row, count, columns_.data(), row_.data(), ADD_VALUES),
          "MatSetValuesBlocked");
  }
}

void CoarseOperators::update(const BrcMatrix& a) {
  share_.apply(a);
  Mat first = levels_[0];
  check(MatZeroEntries(first), "MatZeroEntries");
  add_share_to(first);
  check(MatAssemblyBegin(first, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(first, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  for (std::size_t h = 1; h < levels_.size(); ++h)  // made by the first update, reused after
    check(MatPtAP(levels_[h - 1], prolongations_[h],
                  levels_[h] ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &levels_[h]),
          "MatPtAP");
}

}  // namespace corofem::petsc
