#pragma once
// An observer (core/event_observer.hpp) that keeps what it hears: each section's wall time and
// how often it ran, by name, each event's count, and every solve's statistics with its
// convergence history. A timed run
// attaches one to its solver; the multigrid's parts (multigrid/multigrid_parts.hpp) and the
// record's counts are read from it.
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/event_observer.hpp"

namespace corofem {

/// A solve as EventObserver::solved reported it.
struct LoggedSolve {
  std::string solver;
  int iterations = 0;
  double residual = 0, rate = 0;
  /// The relative residual after each iteration, as the solver reported them (empty for a
  /// direct solve, or a solver that reports no iterations).
  std::vector<double> residuals;
};

class EventLog : public EventObserver {
 public:
  void begin(std::string_view section) override;
  void end(std::string_view section) override;
  void event(std::string_view name) override;
  void iterated(std::string_view solver, int iteration, double residual) override;
  void solved(std::string_view solver, int iterations, double residual, double rate) override;

  /// The wall time of every run of the section `name`, in ms, summed (a section nested in one of
  /// the same name counts in both); 0 for one that never ran.
  double ms(std::string_view name) const;
  /// How often the event `name` was marked.
  int count(std::string_view name) const;
  /// Every solve, in the order they ended.
  const std::vector<LoggedSolve>& solves() const { return solves_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Open {
    std::string name;
    Clock::time_point start;
  };
  mutable std::mutex mutex_;  // marks come from two threads where a solver runs parts side by side
  std::map<std::thread::id, std::vector<Open>>
      open_;  // each thread's open sections, innermost last
  std::map<std::string, double, std::less<>> ms_;
  std::map<std::string, int, std::less<>> counts_;
  std::vector<LoggedSolve> solves_;
  std::map<std::string, std::vector<double>, std::less<>>
      history_;  // each solver's iterations since its last solve ended
};

}  // namespace corofem
