#include "solver/petsc_galerkin.hpp"

#include "core/errors.hpp"

#ifdef COROFEM_HAVE_PETSC
#include "solver/petsc_support.hpp"
#endif

namespace corofem {

#ifndef COROFEM_HAVE_PETSC

struct PetscPtapHierarchy::Impl {};

PetscPtapHierarchy::PetscPtapHierarchy(const BrcMatrix&, const std::vector<Transfer>&) {
  throw InputError("PETSc's MatPtAP needs PETSc, which this build of corofem does not have");
}
PetscPtapHierarchy::~PetscPtapHierarchy() = default;
void PetscPtapHierarchy::update(const BrcMatrix&) {}
int PetscPtapHierarchy::num_levels() const {
  return 0;
}
Eigen::SparseMatrix<double> PetscPtapHierarchy::level(int) const {
  return {};
}

#else

struct PetscPtapHierarchy::Impl {
  explicit Impl(const BrcMatrix& pattern) : fine(pattern) {}
  ~Impl() {
    for (Mat& m : coarse)
      if (m) MatDestroy(&m);
    for (Mat& p : prolongations)
      if (p) MatDestroy(&p);
  }
  petsc::AijFromBrc fine;
  std::vector<Mat> prolongations, coarse;
  bool symbolic_done = false;
};

PetscPtapHierarchy::PetscPtapHierarchy(const BrcMatrix& fine_pattern,
                                       const std::vector<Transfer>& transfers)
    : impl_(std::make_unique<Impl>(fine_pattern)) {
  for (const Transfer& t : transfers) impl_->prolongations.push_back(petsc::prolongation(t));
  impl_->coarse.assign(transfers.size(), nullptr);
}

PetscPtapHierarchy::~PetscPtapHierarchy() = default;

void PetscPtapHierarchy::update(const BrcMatrix& a) {
  impl_->fine.copy(a);
  const MatReuse reuse = impl_->symbolic_done ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
  Mat previous = impl_->fine.mat();
  for (std::size_t h = 0; h < impl_->coarse.size(); ++h) {
    petsc::check(
        MatPtAP(previous, impl_->prolongations[h], reuse, PETSC_DEFAULT, &impl_->coarse[h]),
        "MatPtAP");
    previous = impl_->coarse[h];
  }
  impl_->symbolic_done = true;
}

int PetscPtapHierarchy::num_levels() const {
  return 1 + static_cast<int>(impl_->coarse.size());
}

Eigen::SparseMatrix<double> PetscPtapHierarchy::level(int h) const {
  const Mat m = h == 0 ? impl_->fine.mat() : impl_->coarse[h - 1];
  PetscInt rows = 0, cols = 0;
  petsc::check(MatGetSize(m, &rows, &cols), "MatGetSize");
  std::vector<Eigen::Triplet<double> > triplets;
  for (PetscInt r = 0; r < rows; ++r) {
    PetscInt count = 0;
    const PetscInt* columns = nullptr;
    const PetscScalar* values = nullptr;
    petsc::check(MatGetRow(m, r, &count, &columns, &values), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k) triplets.emplace_back(r, columns[k], values[k]);
    petsc::check(MatRestoreRow(m, r, &count, &columns, &values), "MatRestoreRow");
  }
  Eigen::SparseMatrix<double> out(rows, cols);
  out.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

#endif

}  // namespace corofem
