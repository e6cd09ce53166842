#include "linalg/cholmod_factorization.hpp"

#include <Eigen/CholmodSupport>
#include <mutex>
#include <optional>
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

/// What a call into CHOLMOD holds: for a supernodal factor the BLAS turn and serial OpenMP, for a
/// simplicial one (no BLAS, no OpenMP) nothing.
class CholmodCall {
 public:
  explicit CholmodCall(Factorization kind) {
    if (kind != Factorization::Supernodal) return;
    turn_ = take_blas_turn();
    serial_.emplace();
  }

 private:
  std::unique_lock<std::mutex> turn_;
  std::optional<SerialOpenMp> serial_;
};

}  // namespace

struct CholmodFactorization::Impl {
  // CHOLMOD's own messages off: a failed factorization is reported by the exception below, with
  // the caller's context (and the multigrid coarsest level retries a semidefinite one). A
  // simplicial factor is LL^T too, so that a matrix that is not positive definite fails alike.
  explicit Impl(Factorization kind) : kind(kind) {
    llt.setMode(kind == Factorization::Supernodal ? Eigen::CholmodSupernodalLLt
                                                  : Eigen::CholmodSimplicialLLt);
    llt.cholmod().print = 0;
  }
  Factorization kind;
  // The upper triangle: CHOLMOD's supernodal factorization works on it, a lower one it transposes
  // first.
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Upper> llt;
  bool analyzed = false;
  double lnz = 0, flops = 0;
};

CholmodFactorization::CholmodFactorization(Factorization kind)
    : impl_(std::make_unique<Impl>(kind)) {}
CholmodFactorization::~CholmodFactorization() = default;
CholmodFactorization::CholmodFactorization(CholmodFactorization&&) noexcept = default;
CholmodFactorization& CholmodFactorization::operator=(CholmodFactorization&&) noexcept = default;

void CholmodFactorization::analyze(const Eigen::SparseMatrix<double>& a) {
  const CholmodCall call(impl_->kind);
  impl_->llt.analyzePattern(a);
  impl_->analyzed = true;
  impl_->lnz = impl_->llt.cholmod().lnz;
  impl_->flops = impl_->llt.cholmod().fl;
}

void CholmodFactorization::factorize(const Eigen::SparseMatrix<double>& a) {
  if (!impl_->analyzed) analyze(a);
  const CholmodCall call(impl_->kind);
  impl_->llt.factorize(a);
  if (impl_->llt.info() != Eigen::Success)
    throw std::runtime_error("CHOLMOD: matrix is not positive definite (factorization failed)");
}

Eigen::VectorXd CholmodFactorization::solve(const Eigen::VectorXd& b) const {
  const CholmodCall call(impl_->kind);
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
