#pragma once
// What components mark while they run, for the observers a run attaches (in the manner of
// Ginkgo's loggers and PETSc's log events): sections of work that begin and end (a step's phases;
// a solver's set-up, update and solve parts), events counted (an update, a factorization, a
// refresh, an iteration) and solves finished with their statistics. The numerical code only
// marks: it keeps no clocks, counts or logs, and without an observer a mark costs a test of a null
// pointer. A log of times and counts (core/event_log.hpp), counters of instructions and
// misses (core/section_counter.hpp) or a trace is an observer.
#include <string_view>
#include <utility>
#include <vector>

namespace corofem {

/// Every mark a component makes, each a no-op unless an observer wants it. Sections nest: an end
/// closes the innermost open section of its thread, whose name it repeats. Marks come from one
/// thread at a time, but where a solver runs two parts side by side (the multigrid's coarsest
/// factorization beside its smoothers' set-up), from both: an observer that keeps per-section
/// state keys it by thread (the event log does; the section counter counts one thread's runs).
class EventObserver {
 public:
  virtual ~EventObserver() = default;
  virtual void begin(std::string_view /*section*/) {}
  virtual void end(std::string_view /*section*/) {}
  /// A counted event: a multigrid's "update", "deferred update", "coarsest factorization",
  /// "coarsest shift", "galerkin refresh"; CHOLMOD's "factorization".
  virtual void event(std::string_view /*name*/) {}
  /// An iterative solve's iteration `iteration` (1, 2, ...) ended with the relative residual
  /// `residual` (|b - A x| / |b|): the convergence history, as the solve goes.
  virtual void iterated(std::string_view /*solver*/, int /*iteration*/, double /*residual*/) {}
  /// A solve ended: `solver` ("mgpcg", "jacobi-pcg", ...), its iterations (1 for a direct solve),
  /// the relative residual it reached and its convergence factor (0 where it has none).
  virtual void solved(std::string_view /*solver*/, int /*iterations*/, double /*residual*/,
                      double /*rate*/) {}
};

/// Runs f() as the section `name` of `observer` (f alone when there is none); returns f's result.
template <class F>
decltype(auto) in_section(EventObserver* observer, std::string_view name, F&& f) {
  if (!observer) return std::forward<F>(f)();
  struct End {
    EventObserver* observer;
    std::string_view name;
    ~End() { observer->end(name); }
  } end{observer, name};
  observer->begin(name);
  return std::forward<F>(f)();
}

/// Marks `name` for `observer`, where there is one.
inline void mark_event(EventObserver* observer, std::string_view name) {
  if (observer) observer->event(name);
}

/// Several observers as one: every mark to each, in order.
class EventFanout : public EventObserver {
 public:
  explicit EventFanout(std::vector<EventObserver*> observers) : observers_(std::move(observers)) {}
  void begin(std::string_view section) override {
    for (EventObserver* o : observers_) o->begin(section);
  }
  void end(std::string_view section) override {
    for (EventObserver* o : observers_) o->end(section);
  }
  void event(std::string_view name) override {
    for (EventObserver* o : observers_) o->event(name);
  }
  void iterated(std::string_view solver, int iteration, double residual) override {
    for (EventObserver* o : observers_) o->iterated(solver, iteration, residual);
  }
  void solved(std::string_view solver, int iterations, double residual, double rate) override {
    for (EventObserver* o : observers_) o->solved(solver, iterations, residual, rate);
  }

 private:
  std::vector<EventObserver*> observers_;
};

}  // namespace corofem
