#include "linalg/solver_choice.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/number_text.hpp"

namespace corofem {
namespace {

double steady_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

class TrialSolver : public LinearSolver {
 public:
  TrialSolver(std::vector<std::unique_ptr<LinearSolver>> candidates, SolverTrialSettings settings,
              std::function<double()> clock_ms)
      : candidates_(std::move(candidates)),
        clock_ms_(clock_ms ? std::move(clock_ms) : steady_clock_ms),
        pending_ms_(candidates_.size(), 0.0),
        clear_margin_(settings.clear_margin) {
    if (candidates_.size() < 2)
      throw std::invalid_argument("a solver trial needs two or more candidates");
    if (settings.warmup_solves < 0 || settings.trial_solves <= settings.warmup_solves)
      throw std::invalid_argument("a solver trial needs more trial solves than warm-up solves");
    if (!(settings.clear_margin >= 1))
      throw std::invalid_argument("a solver trial's clear margin is at least 1");
    choice_.trial_solves = settings.trial_solves;
    choice_.warmup_solves = settings.warmup_solves;
    choice_.rule =
        "each candidate solves the first " + std::to_string(settings.trial_solves) +
        " systems from the same start; its cost is the least, over all but the first " +
        std::to_string(settings.warmup_solves) +
        ", of its matrix update since the previous solve plus its solve; the least cost is kept, "
        "at once where it is below 1/" +
        general_number(settings.clear_margin) + " of every other";
    for (const auto& c : candidates_) choice_.candidates.push_back({c->name(), {}, {}, {}});
  }

  std::string name() const override {
    if (chosen_) return "auto: " + choice_.chosen;
    std::string names;
    for (const SolverTrial& t : choice_.candidates) names += (names.empty() ? "" : ", ") + t.name;
    return "auto (trial of " + names + ")";
  }

  const MultigridSolver* multigrid() const override { return used()->multigrid(); }
  const SolverChoice* choice() const override { return &choice_; }
  /// Each candidate marks its own work, its solves in the trial too.
  void observe(EventObserver* events) override {
    for (const auto& c : candidates_) c->observe(events);
  }

  void set_matrix(const BrcMatrix& a) override {
    if (chosen_) return chosen_->set_matrix(a);
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (in_trial(c)) timed(c, [&] { candidates_[c]->set_matrix(a); });
  }

  void take_matrix(BrcMatrix& a) override {
    if (chosen_) return chosen_->take_matrix(a);
    // The candidate whose solutions are used takes the values, as it would alone (the multigrid
    // swaps them instead of copying); the others copy them first.
    const std::size_t taker = first_in_trial();
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (in_trial(c) && c != taker) timed(c, [&] { candidates_[c]->set_matrix(a); });
    timed(taker, [&] { candidates_[taker]->take_matrix(a); });
  }

  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (chosen_) return chosen_->solve(b, x);
    const SolveStats stats = trial_solve(b, x);
    ++solves_;
    const std::size_t best = cheapest();
    if (solves_ == choice_.trial_solves || (best < candidates_.size() && clear_winner(best)))
      choose(best);
    return stats;
  }

 private:
  bool in_trial(std::size_t c) const { return choice_.candidates[c].failure.empty(); }

  std::size_t first_in_trial() const {
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (in_trial(c)) return c;
    return 0;
  }

  /// The candidate whose solutions the run takes: the chosen one, or in the trial the first that
  /// has not failed.
  const LinearSolver* used() const {
    return chosen_ ? chosen_ : candidates_[first_in_trial()].get();
  }

  template <class Work>
  void timed(std::size_t c, Work&& work) {
    const double start = clock_ms_();
    work();
    pending_ms_[c] += clock_ms_() - start;
  }

  /// Ends candidate c's trial (called in its handler, where the exception is current).
  void fail(std::size_t c, const char* why, std::exception_ptr& first_failure) {
    choice_.candidates[c].failure = why;
    if (!first_failure) first_failure = std::current_exception();
  }

  /// Every candidate still in the trial solves the system from x's start, in an order that turns
  /// by one each solve (no candidate always runs on a cache the other warmed). The first
  /// candidate's solution (in the candidates' order) that converged is returned in x.
  SolveStats trial_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    const Eigen::VectorXd start = x;
    const std::size_t n = candidates_.size();
    std::vector<Eigen::VectorXd> solutions(n);
    std::vector<SolveStats> stats(n);
    std::exception_ptr first_failure;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t c = (k + solves_) % n;
      if (!in_trial(c)) continue;
      solutions[c] = start;
      try {
        timed(c, [&] { stats[c] = candidates_[c]->solve(b, solutions[c]); });
      } catch (const NotConverged& e) {
        fail(c, e.what(), first_failure);
      } catch (const NumericalFault& e) {
        fail(c, e.what(), first_failure);
      }
      if (!in_trial(c)) continue;
      choice_.candidates[c].ms.push_back(pending_ms_[c]);
      choice_.candidates[c].iterations.push_back(stats[c].iterations);
      pending_ms_[c] = 0;
    }
    for (std::size_t c = 0; c < n; ++c)
      if (in_trial(c)) {
        x = std::move(solutions[c]);
        return stats[c];
      }
    std::rethrow_exception(first_failure);
  }

  double cost(std::size_t c) const {
    return trial_cost(choice_.candidates[c], choice_.warmup_solves);
  }

  /// The candidate of least cost; candidates_.size() while none has a cost.
  std::size_t cheapest() const {
    std::size_t best = candidates_.size();
    double best_ms = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (cost(c) < best_ms) best_ms = cost(c), best = c;
    return best;
  }

  bool clear_winner(std::size_t best) const {
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (c != best && in_trial(c) && !(cost(c) > clear_margin_ * cost(best))) return false;
    return true;
  }

  /// Keeps `best` and frees the others.
  void choose(std::size_t best) {
    if (best == candidates_.size()) return;  // unreachable: a trial with none left has thrown
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      if (c != best) candidates_[c].reset();
    chosen_ = candidates_[best].get();
    choice_.chosen = choice_.candidates[best].name;
    choice_.decided_after = solves_;
  }

  std::vector<std::unique_ptr<LinearSolver>> candidates_;
  std::function<double()> clock_ms_;
  std::vector<double> pending_ms_;  ///< per candidate: matrix updates since its last solve
  SolverChoice choice_;
  double clear_margin_;
  LinearSolver* chosen_ = nullptr;
  int solves_ = 0;
};

}  // namespace

double trial_cost(const SolverTrial& trial, int warmup_solves) {
  if (!trial.failure.empty() || static_cast<int>(trial.ms.size()) <= warmup_solves)
    return std::numeric_limits<double>::infinity();
  return *std::min_element(trial.ms.begin() + warmup_solves, trial.ms.end());
}

std::unique_ptr<LinearSolver> make_trial_solver(
    std::vector<std::unique_ptr<LinearSolver>> candidates, SolverTrialSettings settings,
    std::function<double()> clock_ms) {
  return std::make_unique<TrialSolver>(std::move(candidates), settings, std::move(clock_ms));
}

}  // namespace corofem
