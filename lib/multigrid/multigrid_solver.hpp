#pragma once
// Geometric multigrid with Galerkin coarse operators (paper section 4; Georgii and Westermann
// 2005): V-cycles with a registered smoother (block Gauss-Seidel by default) and CHOLMOD on the
// coarsest level, as a solver ("multigrid") or as the preconditioner of CG ("mgpcg").
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include "core/event_observer.hpp"
#include "linalg/linear_solver.hpp"
#include "linalg/smoother.hpp"
#include "multigrid/hierarchy.hpp"
#include "multigrid/hierarchy_builder.hpp"
#include "multigrid/solver_part.hpp"

namespace corofem {

/// The cycle's shape: V visits each coarser level once per visit of the level above; W twice (the
/// coarse correction iterated, for where it is the weak part; the coarsest level, solved exactly,
/// once).
enum class CycleShape { V, W };
inline constexpr NameTable<CycleShape, 2> kCycleShapes{
    {{{CycleShape::V, "V"}, {CycleShape::W, "W"}}}};

/// The parameters of every component, written into every record of a multigrid solve
/// (io/multigrid_record.hpp).
struct MultigridParams {
  HierarchyParams hierarchy;  ///< builder and level count
  int pre_smoothing = 1;      ///< smoothings before the coarse correction
  int post_smoothing = 1;     ///< smoothings after it
  CycleShape cycle = CycleShape::V;
  int vcycles = 0;           ///< multigrid: fixed count; 0 = iterate to the tolerance
  int max_iterations = 500;  ///< cap on V-cycles / CG iterations
  double tolerance = 1e-8;   ///< relative residual |b - A x| / |b|
  GalerkinMethod galerkin = GalerkinMethod::Gather;
  /// The smoother of every level but the coarsest, by its registered name (linalg/smoother.hpp):
  /// hybrid Gauss-Seidel, the one that threads with the sequential locality.
  std::string smoother = "hybrid";
  /// The smoother's own settings (SmootherTraits::parameters; those it lacks at their defaults).
  Parameters smoother_parameters{};
  /// MG-PCG at two or more threads and three or more levels: the coarsest factorization beside the
  /// next solve's initial residual and first descent (see MultigridSolver::defers_update), not in
  /// the update.
  bool overlap_factorization = true;
  /// The coarsest factorization is kept while the coarsest operator's values differ from those it
  /// factored by less than this, relative, in the Frobenius norm (0: refactored at every update).
  /// The factor of a nearby SPD operator is still an SPD coarse solve, so the V-cycle stays an SPD
  /// preconditioner and MG-PCG meets its tolerance; only its rate can suffer. A scene's stationary
  /// multigrid defaults to 0: without CG, a stale coarse solve can make its cycle diverge. Measured
  /// in lib/docs/multigrid-update-notes.md, "The coarsest factor kept while the operator barely
  /// moves".
  double coarsest_refactor_change = 0.03;
  /// The coarse operators E = R A R^T are recomputed when the fine operator's stiffness moved by
  /// this much, relative, since they were last (0: at every update, the paper's). What moves is
  /// measured on the off-diagonal entries of A's diagonal blocks: stiffness alone (the lumped mass
  /// is diagonal), and turned by the rotations as every block is. Between refreshes the V-cycle
  /// runs on the fine level's new operator and the coarse levels' last ones: still an SPD
  /// preconditioner, so MG-PCG meets its tolerance and only its rate can suffer.
  double galerkin_refresh_change = 0;
};

class MultigridSolver : public LinearSolver {
 public:
  /// `built`: the transfers from hierarchy_builder.hpp (fixed fine vertices, whose rows are
  /// identity in A, take no part in them). `events` (kept, may be null; observe() changes it):
  /// hears every part as a section from the set-up on (kSolverParts), the events it counts
  /// ("update", "deferred update", "galerkin refresh", "coarsest factorization", "coarsest
  /// shift") and every solve's statistics.
  MultigridSolver(const BrcMatrix& pattern, BuiltHierarchy built, const MultigridParams& params,
                  bool as_preconditioner, EventObserver* events = nullptr);
  ~MultigridSolver() override;

  std::string name() const override { return preconditioner_ ? "mgpcg" : "multigrid"; }
  void set_matrix(const BrcMatrix& a) override;
  void take_matrix(BrcMatrix& a) override;  ///< the fine values swapped in, not copied
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  const MultigridSolver* multigrid() const override { return this; }

  /// One V-cycle from level h for A_h x = b, x the initial guess on entry; `zero_guess`: x starts
  /// at 0 whatever it holds (a correction: every coarse level, and the preconditioner), so the
  /// first forward sweep reads half the matrix.
  void vcycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_guess);
  /// Whether an update runs the coarsest factorization beside the smoothers' set-up (and, deferred,
  /// beside the next solve's start): overlap_factorization, two or more threads and three or more
  /// levels (with two, the work beside it is too small to pay for a thread of its own).
  bool overlaps_update() const;
  /// Whether set_matrix leaves the coarsest factorization and the smoothers' set-up to the next
  /// solve (MG-PCG where the update overlaps, from the second update on, in the updates that
  /// refactor the coarsest level): that solve runs them beside its initial residual and its first
  /// V-cycle's descent. Their time then counts in the solve, not the update.
  bool defers_update() const;
  /// Whether the last set_matrix's factorization and smoothers' set-up still wait for a solve.
  bool update_deferred() const { return update_pending_; }
  const MultigridHierarchy& hierarchy() const { return hierarchy_; }
  const MultigridParams& params() const { return params_; }
  /// Level h's smoother (h below the coarsest level).
  const Smoother& smoother(int h) const { return *smoothers_.at(static_cast<std::size_t>(h)); }
  /// The coarsest level's Cholesky factor: entries of L and flops per factorization (CHOLMOD's
  /// analysis; 0 before the first set_matrix).
  double coarsest_factor_nonzeros() const;
  double coarsest_factorization_flops() const;
  /// Where each coarse level came from (level h + 1 at h).
  const std::vector<CoarseLevelOrigin>& level_origins() const { return level_origins_; }
  /// Why the hierarchy has fewer levels than its params ask for (BuiltHierarchy::ended_early).
  const std::string& ended_early() const { return ended_early_; }

 private:
  SolveStats run_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// MG-PCG whose update is pending: the initial residual and the first V-cycle's descent on one
  /// thread, the coarsest factorization on another, then CG.
  SolveStats run_overlapped_pcg(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  void update_levels();  ///< after the Galerkin products: the smoothers and the coarsest factor
  /// An update: the fine values by `fine` (a copy or a swap), and the coarse operators where the
  /// fine stiffness moved enough (galerkin_refresh_change).
  template <class F>
  void update_from(const BrcMatrix& a, const F& fine);
  /// Whether the fine operator's stiffness moved from that of the last refresh by
  /// params_.galerkin_refresh_change or more (always before the first, and with 0).
  bool fine_moved(const BrcMatrix& a) const;
  /// The fine operator's stiffness probe (galerkin_refresh_change's measure), into `probe`.
  void stiffness_probe(const BrcMatrix& a, std::vector<double>& probe) const;
  /// Runs a pending update: the coarsest factorization on one thread, and on another the
  /// smoothers' set-up, then `beside` (work that does not need the factor).
  void complete_update(const std::function<void()>& beside = {});
  /// The coarsest factorization, and a record of the values it factorized.
  void update_coarsest();
  void factorize_coarsest();
  /// Whether the coarsest level's values moved from those last factorized by
  /// params_.coarsest_refactor_change or more (always before the first factorization).
  bool coarsest_moved() const;
  void cycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_guess);
  /// How many cycles on level h + 1 make level h's coarse correction.
  int coarse_visits(int h) const;
  /// Level h's part of a V-cycle before its coarse correction (pre-smoothing, the residual
  /// restricted into coarse_b_[h + 1]), and the part after it (the correction prolongated into
  /// x, post-smoothing).
  void descend(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_guess);
  void ascend(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The rest of a V-cycle from level 0 whose descent has run: the coarsest solve, the ascents.
  void finish_cycle(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// Runs f as the section `part` for the observer.
  template <class F>
  void part(SolverPart part, const F& f);
  MultigridParams params_;
  bool preconditioner_;
  MultigridHierarchy hierarchy_;
  std::vector<std::unique_ptr<Smoother>> smoothers_;  ///< one per level but the coarsest
  struct Coarsest;
  std::unique_ptr<Coarsest> coarsest_;
  std::vector<Eigen::VectorXd> residual_, coarse_b_, coarse_x_;  // scratch per level
  bool update_pending_ = false;
  bool refactor_pending_ = false;  ///< the pending update factorizes the coarsest level
  /// Once a coarsest factorization needed the semidefinite shift, every later one has it (the
  /// pattern of dependence does not change with the values: factorize_coarsest).
  bool coarsest_shifted_ = false;
  std::vector<double> factored_values_;  ///< the coarsest level's values when last factorized
  std::vector<double> refreshed_probe_;  ///< the fine stiffness probe at the last refresh
  std::vector<int> fine_diagonal_;       ///< the fine pattern's diagonal block of each row
  bool coarse_pending_ = false;          ///< the pending update recomputed the coarse operators
  std::vector<CoarseLevelOrigin> level_origins_;
  std::string ended_early_;
};

}  // namespace corofem
