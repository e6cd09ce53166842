#include "multigrid/multigrid_solver.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "linalg/cholmod_factorization.hpp"
#include "linalg/preconditioned_cg.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

namespace {

/// Whether `now` differs from `then` by `limit` or more, relative, in the Frobenius norm (a NaN
/// counts as moved). Serial, in one order: the decision, and so the bits, are the same at every
/// thread count.
bool moved_beyond(const std::vector<double>& now, const std::vector<double>& then, double limit) {
  double change = 0, size = 0;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const double d = now[k] - then[k];
    change += d * d;
    size += then[k] * then[k];
  }
  return !(change < limit * limit * size);
}

}  // namespace

template <class F>
void MultigridSolver::part(SolverPart part, const F& f) {
  in_section(events_, kSolverParts.name(part), f);
}

struct MultigridSolver::Coarsest {
  std::optional<BrcToEigen> converter;
  CholmodFactorization cholmod;
};

MultigridSolver::MultigridSolver(const BrcMatrix& pattern, BuiltHierarchy built,
                                 const MultigridParams& params, bool as_preconditioner,
                                 EventObserver* events)
    : params_(params),
      preconditioner_(as_preconditioner),
      hierarchy_(pattern, std::move(built.transfers)),
      coarsest_(std::make_unique<Coarsest>()),
      residual_(hierarchy_.num_levels()),
      coarse_b_(hierarchy_.num_levels()),
      coarse_x_(hierarchy_.num_levels()),
      level_origins_(std::move(built.levels)),
      ended_early_(std::move(built.ended_early)) {
  events_ = events;
  fine_diagonal_.resize(pattern.block_rows);
  for (int i = 0; i < pattern.block_rows; ++i) fine_diagonal_[i] = pattern.find(i, i);
  for (int h = 0; h + 1 < hierarchy_.num_levels(); ++h)
    smoothers_.push_back(make_smoother(params_.smoother, params_.smoother_parameters));
  // The method's streams now, in the set-up, not in the first step's update.
  part(SolverPart::GalerkinStreams, [&] { hierarchy_.prepare(params_.galerkin); });
}

MultigridSolver::~MultigridSolver() = default;

double MultigridSolver::coarsest_factor_nonzeros() const {
  return coarsest_->cholmod.factor_nonzeros();
}
double MultigridSolver::coarsest_factorization_flops() const {
  return coarsest_->cholmod.factorization_flops();
}

void MultigridSolver::set_matrix(const BrcMatrix& a) {
  update_from(a, [&] { hierarchy_.set_fine(a); });
}

void MultigridSolver::take_matrix(BrcMatrix& a) {
  update_from(a, [&] { hierarchy_.take_fine(a); });
}

template <class F>
void MultigridSolver::update_from(const BrcMatrix& a, const F& fine) {
  mark_event(events_, "update");
  part(SolverPart::Galerkin, [&] {
    // Probed before `fine` may take a's values.
    coarse_pending_ = hierarchy_.num_levels() == 1 || fine_moved(a);
    if (coarse_pending_ && params_.galerkin_refresh_change > 0)
      stiffness_probe(a, refreshed_probe_);
    fine();
    if (!coarse_pending_) return;
    mark_event(events_, "galerkin refresh");
    hierarchy_.update_coarse(params_.galerkin);
  });
  update_levels();
}

void MultigridSolver::stiffness_probe(const BrcMatrix& a, std::vector<double>& probe) const {
  // The off-diagonal entries of each diagonal block (the lumped mass touches only the diagonal).
  const int n = a.block_rows;
  probe.resize(6 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double* b = a.values.data() + 9 * static_cast<std::size_t>(fine_diagonal_[i]);
    const double off[6] = {b[1], b[2], b[3], b[5], b[6], b[7]};
    std::copy(off, off + 6, probe.begin() + 6 * static_cast<std::ptrdiff_t>(i));
  }
}

bool MultigridSolver::fine_moved(const BrcMatrix& a) const {
  if (refreshed_probe_.empty() || params_.galerkin_refresh_change <= 0) return true;
  std::vector<double> now;
  stiffness_probe(a, now);
  return moved_beyond(now, refreshed_probe_, params_.galerkin_refresh_change);
}

void MultigridSolver::update_levels() {
  // The coarsest factorization is serial (CHOLMOD, linalg/cholmod_factorization.cpp). MG-PCG's
  // initial residual needs neither it nor the smoothers, and its first V-cycle's descent needs only
  // the smoothers: so at two or more threads the update stops after the Galerkin products and the
  // next solve runs the factorization on one thread beside those on another
  // (run_overlapped_pcg). The first update, which analyses the pattern, runs in full here, and so
  // does one that keeps the coarsest factor (the smoothers' set-up then has both threads).
  part(SolverPart::Coarsest, [&] { refactor_pending_ = coarse_pending_ && coarsest_moved(); });
  update_pending_ = true;
  if (!(defers_update() && refactor_pending_ && coarsest_->converter)) complete_update();
}

bool MultigridSolver::coarsest_moved() const {
  if (factored_values_.empty() || params_.coarsest_refactor_change <= 0) return true;
  // A NaN refactors (and the factorization reports it).
  return moved_beyond(hierarchy_.matrix(hierarchy_.num_levels() - 1).values, factored_values_,
                      params_.coarsest_refactor_change);
}

bool MultigridSolver::overlaps_update() const {
  // With two levels the work beside the factorization is the fine level's pre-smoothing alone,
  // which then runs on one thread instead of two: that costs what the overlap saves or more. From
  // three levels the descent through the levels between pays (lib/docs/multigrid-update-notes.md,
  // "The update beside the solve").
  return params_.overlap_factorization && thread_count() > 1 && hierarchy_.num_levels() >= 3;
}

bool MultigridSolver::defers_update() const {
  return overlaps_update() && preconditioner_;
}

void MultigridSolver::complete_update(const std::function<void()>& beside) {
  if (!update_pending_) return;
  update_pending_ = false;
  // Where the update overlaps (overlaps_update) the parts run side by side, each marking its own
  // sections on its own thread (the observers key them by thread: core/event_observer.hpp).
  const int last = hierarchy_.num_levels() - 1;
  auto factorize = [&] {
    if (refactor_pending_) part(SolverPart::Coarsest, [&] { update_coarsest(); });
  };
  auto rest = [&] {
    part(SolverPart::Smoothers, [&] {
      // The coarse levels' smoothers again only where their operators were recomputed.
      for (int h = 0; h < (coarse_pending_ ? last : std::min(last, 1)); ++h)
        smoothers_[h]->set_matrix(hierarchy_.matrix(h));
    });
    if (beside) beside();
  };
  if (overlaps_update() && refactor_pending_) {
    run_side_by_side(factorize, rest);
  } else {  // the same operations, one after the other: the same bits
    factorize();
    rest();
  }
}

void MultigridSolver::update_coarsest() {
  // Its values are kept only once factorized: a failed factorization (an indefinite operator,
  // which a Newton caller then replaces) leaves none, so the next update refactors.
  factored_values_.clear();
  factorize_coarsest();
  mark_event(events_, "coarsest factorization");
  factored_values_ = hierarchy_.matrix(hierarchy_.num_levels() - 1).values;
}

void MultigridSolver::factorize_coarsest() {
  const int last = hierarchy_.num_levels() - 1;
  if (!coarsest_->converter) {
    coarsest_->converter.emplace(hierarchy_.matrix(last), BrcToEigen::Part::SymmetricUpper);
    coarsest_->cholmod.analyze(coarsest_->converter->matrix());
  } else {
    coarsest_->converter->update(hierarchy_.matrix(last));
  }
  // E = R A R^T is only semidefinite when lattice vertices of thin parts have linearly dependent
  // prolongation columns. Then null(E) = null(R^T): the restricted residual has no component
  // there and R^T annihilates whatever the solve puts there, so a tiny diagonal shift changes
  // the coarse correction only at the shift's relative size. Once needed, it is kept (the
  // pattern of dependence does not change with the values).
  if (!coarsest_shifted_) {
    try {
      coarsest_->cholmod.factorize(coarsest_->converter->matrix());
      return;
    } catch (const std::runtime_error&) {
    }
  }
  Eigen::SparseMatrix<double> shifted = coarsest_->converter->matrix();
  const double shift = 1e-10 * shifted.diagonal().cwiseAbs().mean();
  for (int i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) += shift;
  try {
    coarsest_->cholmod.factorize(shifted);
    coarsest_shifted_ = true;
    mark_event(events_, "coarsest shift");
  } catch (const std::runtime_error& e) {
    throw NumericalFault(std::string("multigrid coarsest level: ") + e.what());
  }
}

void MultigridSolver::vcycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_guess) {
  complete_update();
  cycle(h, b, x, zero_guess);
}

void MultigridSolver::cycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_guess) {
  if (h == hierarchy_.num_levels() - 1) {
    part(SolverPart::CoarsestSolve, [&] { x = coarsest_->cholmod.solve(b); });
    return;
  }
  descend(h, b, x, zero_guess);
  for (int k = 0; k < coarse_visits(h); ++k)
    cycle(h + 1, coarse_b_[h + 1], coarse_x_[h + 1], k == 0);
  ascend(h, b, x);
}

int MultigridSolver::coarse_visits(int h) const {
  // The W-cycle iterates level h + 1's cycle from its own last iterate; the coarsest level is
  // solved exactly, so once is enough there.
  return h + 1 == hierarchy_.num_levels() - 1 || params_.cycle == CycleShape::V ? 1 : 2;
}

void MultigridSolver::descend(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              bool zero_guess) {
  const BrcMatrix& a = hierarchy_.matrix(h);
  const bool fine = h == 0;
  bool formed = false;  // the smoother formed the residual in passing: it counts in the smoothing
  part(fine ? SolverPart::FineSmooth : SolverPart::CoarseLevels, [&] {
    formed = smoothers_[h]->pre_smooth(a, b, x, params_.pre_smoothing, zero_guess, residual_[h]);
  });
  if (!formed)
    part(fine ? SolverPart::FineResidual : SolverPart::CoarseLevels,
         [&] { a.residual(b, x, residual_[h]); });
  part(fine ? SolverPart::FineTransfer : SolverPart::CoarseLevels,
       [&] { hierarchy_.transfer(h).restrict_to(residual_[h], coarse_b_[h + 1]); });
}

void MultigridSolver::ascend(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const bool fine = h == 0;
  part(fine ? SolverPart::FineTransfer : SolverPart::CoarseLevels,
       [&] { hierarchy_.transfer(h).prolongate_add(coarse_x_[h + 1], x); });
  part(fine ? SolverPart::FineSmooth : SolverPart::CoarseLevels,
       [&] { smoothers_[h]->post_smooth(hierarchy_.matrix(h), b, x, params_.post_smoothing); });
}

void MultigridSolver::finish_cycle(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int last = hierarchy_.num_levels() - 1;
  cycle(last, coarse_b_[last], coarse_x_[last], true);
  for (int h = last - 1; h >= 0; --h) {
    // Level h + 1's first cycle is complete here; a W-cycle repeats it.
    for (int k = 1; k < coarse_visits(h); ++k)
      cycle(h + 1, coarse_b_[h + 1], coarse_x_[h + 1], false);
    ascend(h, h == 0 ? b : coarse_b_[h], h == 0 ? x : coarse_x_[h]);
  }
}

SolveStats MultigridSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const SolveStats stats = run_solve(b, x);
  report_solved(stats);
  return stats;
}

SolveStats MultigridSolver::run_overlapped_pcg(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  // The same operations in the same order as complete_update() and then preconditioned_cg():
  // the same bits. The descent runs whether or not CG then asks for it (a start that already
  // meets the tolerance wastes it, beside the factorization it waits for anyway).
  const BrcMatrix& a = hierarchy_.matrix(0);
  const int last = hierarchy_.num_levels() - 1;
  Eigen::VectorXd r0, z0;
  mark_event(events_, "deferred update");
  complete_update([&] {
    start_iterative_solve(b, x);  // x sized as CG sizes it
    a.residual(b, x, r0);
    descend(0, r0, z0, true);
    for (int h = 1; h < last; ++h) descend(h, coarse_b_[h], coarse_x_[h], true);
  });
  bool descended = true;
  return preconditioned_cg(
      a, b, x,
      [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
        if (!descended) return cycle(0, r, z, true);
        descended = false;  // CG's first call: r is r0
        z.swap(z0);
        finish_cycle(r, z);
      },
      params_.tolerance, params_.max_iterations, "mgpcg", &r0, events_);
}

SolveStats MultigridSolver::run_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const BrcMatrix& a = hierarchy_.matrix(0);
  if (preconditioner_ && update_pending_) return run_overlapped_pcg(b, x);
  complete_update();
  if (preconditioner_)
    return preconditioned_cg(
        a, b, x, [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { cycle(0, r, z, true); },
        params_.tolerance, params_.max_iterations, "mgpcg", nullptr, events_);
  SolveStats stats;
  const double b_norm = start_iterative_solve(b, x);
  if (b_norm == 0) return stats;
  Eigen::VectorXd r;
  a.residual(b, x, r);
  const double r0 = r.norm();
  const int cap = params_.vcycles > 0 ? params_.vcycles : params_.max_iterations;
  double rk = r0;
  for (int k = 0; k < cap; ++k) {
    if (params_.vcycles == 0 && rk <= params_.tolerance * b_norm) break;
    cycle(0, b, x, false);
    a.residual(b, x, r);
    rk = r.norm();
    ++stats.iterations;
    if (events_) events_->iterated("multigrid", stats.iterations, rk / b_norm);
    if (!std::isfinite(rk)) throw NumericalFault("multigrid: residual became non-finite");
  }
  stats.residual = rk / b_norm;
  stats.convergence_factor =
      stats.iterations > 0 && r0 > 0 ? std::pow(rk / r0, 1.0 / stats.iterations) : 0;
  if (params_.vcycles == 0) require_converged(stats, params_.tolerance, "multigrid", "V-cycles");
  return stats;
}

}  // namespace corofem
