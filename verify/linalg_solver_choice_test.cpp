// analysis.solver "auto" (linalg/solver_choice.hpp): the trial's rule, against candidates whose
// costs a test clock sets, so that every choice here is decided by the rule and not by the
// machine's noise. What auto picks on real scenes is measured, not asserted (lib/docs/solver-choice
// in the scene format's page, and the closing note of issue 70).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/event_log.hpp"
#include "linalg/solver_choice.hpp"

namespace corofem {
namespace {

/// A candidate that "solves" x = b / divisor (so a test sees whose solution came back), takes
/// `solve_ms` per solve (the first `first_solve_ms`) and `matrix_ms` per matrix on the test clock,
/// and fails with NotConverged at solve number `fails_at` (1-based; 0: never).
struct FakeCandidate : LinearSolver {
  FakeCandidate(std::string name, double divisor, double& clock, std::vector<double> solve_ms,
                double matrix_ms = 0, int fails_at = 0)
      : name_(std::move(name)),
        divisor_(divisor),
        clock_(clock),
        solve_ms_(std::move(solve_ms)),
        matrix_ms_(matrix_ms),
        fails_at_(fails_at) {}
  std::string name() const override { return name_; }
  void set_matrix(const BrcMatrix& a) override {
    clock_ += matrix_ms_;
    ++matrices;
    last_value = a.values.empty() ? 0 : a.values.front();
  }
  void take_matrix(BrcMatrix& a) override {
    set_matrix(a);
    ++taken;
    a.values.assign(a.values.size(), -1);  // what a swap leaves is unspecified: here, garbage
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    ++solves;
    const double ms = solve_ms_[std::min<std::size_t>(solves - 1, solve_ms_.size() - 1)];
    clock_ += ms;
    if (solves == fails_at_) throw NotConverged(name_ + ": did not converge");
    x = b / divisor_;
    const SolveStats stats{static_cast<int>(10 * divisor_), 0, 0};
    report_solved(stats);
    return stats;
  }

  int matrices = 0, taken = 0, solves = 0;
  double last_value = 0;

 private:
  std::string name_;
  double divisor_;
  double& clock_;
  std::vector<double> solve_ms_;
  double matrix_ms_;
  int fails_at_;
};

struct Trial {
  double clock = 0;
  FakeCandidate* first = nullptr;
  FakeCandidate* second = nullptr;
  std::unique_ptr<LinearSolver> solver;

  Trial(std::vector<double> first_ms, std::vector<double> second_ms, double first_matrix_ms = 0,
        double second_matrix_ms = 0, int first_fails_at = 0, int second_fails_at = 0,
        SolverTrialSettings settings = {}) {
    auto a = std::make_unique<FakeCandidate>("first", 1, clock, std::move(first_ms),
                                             first_matrix_ms, first_fails_at);
    auto b = std::make_unique<FakeCandidate>("second", 2, clock, std::move(second_ms),
                                             second_matrix_ms, second_fails_at);
    first = a.get();
    second = b.get();
    std::vector<std::unique_ptr<LinearSolver>> candidates;
    candidates.push_back(std::move(a));
    candidates.push_back(std::move(b));
    solver = make_trial_solver(std::move(candidates), settings, [this] { return clock; });
  }

  /// One step: a matrix, then a solve of b = (1, 1, 1); returns x[0] (1: the first's, 0.5: the
  /// second's).
  double step() {
    BrcMatrix a;
    a.values = {7.0};
    solver->take_matrix(a);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    solver->solve(Eigen::VectorXd::Ones(3), x);
    return x[0];
  }
};

TEST(SolverChoice, KeepsTheLeastCostAfterTheWarmupCountingItsMatrixUpdates) {
  // The second's first solve carries a one-time set-up (100 ms); after it, its matrix plus solve
  // (1 + 3 ms) beats the first's 5 ms, by less than the clear margin: all four trial solves run.
  Trial t({5}, {100, 3}, 0, 1);
  for (int s = 0; s < 3; ++s) EXPECT_EQ(t.step(), 1.0) << "trial solve " << s + 1;
  EXPECT_EQ(t.solver->choice()->chosen, "");
  EXPECT_EQ(t.step(), 1.0);  // the fourth trial solve still returns the first's solution
  const SolverChoice& c = *t.solver->choice();
  EXPECT_EQ(c.chosen, "second");
  EXPECT_EQ(c.decided_after, 4);
  EXPECT_EQ(c.candidates[0].ms, (std::vector<double>{5, 5, 5, 5}));
  EXPECT_EQ(c.candidates[1].ms, (std::vector<double>{101, 4, 4, 4}));
  EXPECT_EQ(c.candidates[1].iterations, (std::vector<int>{20, 20, 20, 20}));
  EXPECT_EQ(t.solver->name(), "auto: second");
  // From here only the second runs.
  FakeCandidate* kept = t.second;
  EXPECT_EQ(t.step(), 0.5);
  EXPECT_EQ(kept->solves, 5);
  EXPECT_EQ(kept->matrices, 5);
}

TEST(SolverChoice, AnObserverHearsEveryCandidatesSolves) {
  // observe() reaches each candidate: in the trial both report their solves, after it the chosen
  // one alone (core/event_observer.hpp). The second wins clearly at the second solve.
  Trial t({50}, {1});
  EventLog log;
  t.solver->observe(&log);
  for (int s = 0; s < 3; ++s) t.step();
  ASSERT_EQ(t.solver->choice()->chosen, "second");
  std::vector<std::string> solvers;
  for (const LoggedSolve& s : log.solves()) solvers.push_back(s.solver);
  EXPECT_EQ(solvers, (std::vector<std::string>{"first", "second", "second", "first", "second"}));
}

TEST(SolverChoice, TheWarmupDoesNotDecide) {
  // Neither a one-time set-up (the second's 100 ms) nor an atypically cheap first solve (the
  // first's 0.5 ms, as from rest) counts.
  Trial t({0.5, 5}, {100, 4});
  for (int s = 0; s < 4; ++s) t.step();
  EXPECT_EQ(t.solver->choice()->chosen, "second");
  EXPECT_EQ(t.solver->choice()->decided_after, 4);
  // Counting the first solve, the second's one-time 100 ms makes the first a clear winner at once.
  Trial all_counted({5}, {100, 3}, 0, 0, 0, 0, {.trial_solves = 4, .warmup_solves = 0});
  all_counted.step();
  EXPECT_EQ(all_counted.solver->choice()->chosen, "first");
  EXPECT_EQ(all_counted.solver->choice()->decided_after, 1);
}

TEST(SolverChoice, AClearWinnerEndsTheTrialAtTheFirstSolveAfterTheWarmup) {
  Trial t({10}, {4.9});  // 10 > 2 x 4.9
  t.step();
  EXPECT_EQ(t.solver->choice()->chosen, "");  // the warm-up decides nothing
  t.step();
  EXPECT_EQ(t.solver->choice()->chosen, "second");
  EXPECT_EQ(t.solver->choice()->decided_after, 2);
  Trial close({10}, {5.1});  // within the margin: the trial runs its four solves
  for (int s = 0; s < 3; ++s) close.step();
  EXPECT_EQ(close.solver->choice()->chosen, "");
  close.step();
  EXPECT_EQ(close.solver->choice()->chosen, "second");
}

TEST(SolverChoice, TheCandidatesSolveTheSameSystemFromTheSameStartAndSeeTheValues) {
  Trial t({1}, {1});
  t.step();
  // The first candidate (whose solution the trial returns) takes the values, as it would alone;
  // the other copied them before (7, not -1).
  EXPECT_EQ(t.first->taken, 1);
  EXPECT_EQ(t.second->taken, 0);
  EXPECT_EQ(t.first->last_value, 7.0);
  EXPECT_EQ(t.second->last_value, 7.0);
  EXPECT_EQ(t.first->solves, 1);
  EXPECT_EQ(t.second->solves, 1);
}

TEST(SolverChoice, AFailedCandidateIsNeverChosenAndTheOtherSolvesOn) {
  Trial t({1}, {5}, 0, 0, /*first_fails_at=*/2);
  EXPECT_EQ(t.step(), 1.0);
  EXPECT_EQ(t.step(), 0.5);  // the first failed: the second's solution
  for (int s = 0; s < 2; ++s) t.step();
  const SolverChoice& c = *t.solver->choice();
  EXPECT_EQ(c.chosen, "second");
  EXPECT_NE(c.candidates[0].failure.find("did not converge"), std::string::npos);
  EXPECT_EQ(c.candidates[0].ms.size(), 1u);
  // Both failing: the solve fails as a solver's would.
  Trial both({1}, {1}, 0, 0, 1, 1);
  EXPECT_THROW(both.step(), NotConverged);
}

TEST(SolverChoice, ARunThatEndsWithinTheTrialHasChosenNothing) {
  Trial t({1}, {5});
  t.step();
  EXPECT_EQ(t.solver->choice()->chosen, "");
  EXPECT_EQ(t.solver->choice()->decided_after, 0);
  EXPECT_EQ(t.solver->name(), "auto (trial of first, second)");
}

TEST(SolverChoice, RefusesATrialThatCannotDecide) {
  std::vector<std::unique_ptr<LinearSolver>> one;
  double clock = 0;
  one.push_back(std::make_unique<FakeCandidate>("only", 1, clock, std::vector<double>{1}));
  EXPECT_THROW(make_trial_solver(std::move(one)), std::invalid_argument);
  EXPECT_THROW(Trial({1}, {1}, 0, 0, 0, 0, {.trial_solves = 1, .warmup_solves = 1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace corofem
