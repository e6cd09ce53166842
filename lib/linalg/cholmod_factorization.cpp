#include "linalg/cholmod_factorization.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>
#ifdef COROFEM_HAVE_OPENMP
#include <omp.h>
#endif

#include "linalg/blas_turn.hpp"

namespace corofem {

namespace {

/// Debian's CHOLMOD (SuiteSparse 5) opens OpenMP regions of a fixed CHOLMOD_OMP_NUM_THREADS = 4
/// threads inside its supernodal factorization, whatever the machine, which on 2 cores
/// oversubscribes them several times over: while one is alive, every OpenMP region of this
/// process runs on one thread.
class SerialOpenMp {
 public:
#ifdef COROFEM_HAVE_OPENMP
  SerialOpenMp() : saved_(omp_get_max_active_levels()) {
    omp_set_max_active_levels(0);
  }
  ~SerialOpenMp() {
    omp_set_max_active_levels(saved_);
  }

 private:
  int saved_;
#endif
};

}  // namespace

struct CholmodFactorization::Impl {
  // CHOLMOD's own messages off: a failed factorization is reported by the exception below, with
  // the caller's context (and the multigrid coarsest level retries a semidefinite one).
  Impl() { llt.cholmod().print = 0; }
  // The upper triangle: CHOLMOD's supernodal factorization works on it, a lower one it transposes
  // first.
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
  bool analyzed = false;
  double lnz = 0, flops = 0;
};

CholmodFactorization::CholmodFactorization() : impl_(std::make_unique<Impl>()) {}
CholmodFactorization::~CholmodFactorization() = default;
CholmodFactorization::CholmodFactorization(CholmodFactorization&&) noexcept = default;
CholmodFactorization& CholmodFactorization::operator=(CholmodFactorization&&) noexcept = default;

void CholmodFactorization::analyze(const Eigen::SparseMatrix<double>& a) {
  const auto turn = take_blas_turn();
  const SerialOpenMp serial;
  impl_->llt.analyzePattern(a);
  impl_->analyzed = true;
  impl_->lnz = impl_->llt.cholmod().lnz;
  impl_->flops = impl_->llt.cholmod().fl;
}

void CholmodFactorization::factorize(const Eigen::SparseMatrix<double>& a) {
  if (!impl_->analyzed) analyze(a);
  const auto turn = take_blas_turn();
  const SerialOpenMp serial;
  impl_->llt.factorize(a);
  if (impl_->llt.info() != Eigen::Success)
    throw std::runtime_error("CHOLMOD: matrix is not positive definite (factorization failed)");
}

Eigen::VectorXd CholmodFactorization::solve(const Eigen::VectorXd& b) const {
  const auto turn = take_blas_turn();
  const SerialOpenMp serial;
  Eigen::VectorXd x = impl_->llt.solve(b);
  if (impl_->llt.info() != Eigen::Success) throw std::runtime_error("CHOLMOD: solve failed");
  return x;
}

double CholmodFactorization::factor_nonzeros() const {
  return impl_->lnz;
}
double CholmodFactorization::factorization_flops() const {
  return impl_->flops;
}

}  // namespace corofem
