#pragma once
// Sections of work that components mark as they run (a step's phases, a solver's parts), for the
// observers a run attaches: a clock, counters of instructions and cache misses, a log. In the
// manner of PETSc's log events and Ginkgo's loggers, the numerical code only marks; it keeps no
// counts, and without an observer a mark costs a test of a null pointer.
#include <string_view>
#include <utility>

namespace corofem {

/// Receives the begin and end of every section, from one thread at a time. Sections nest: an end
/// closes the innermost open section, whose name it repeats.
class SectionObserver {
 public:
  virtual ~SectionObserver() = default;
  virtual void begin(std::string_view section) = 0;
  virtual void end(std::string_view section) = 0;
};

/// Runs f() as the section `name` of `observer` (f alone when there is none); returns f's result.
template <class F>
decltype(auto) in_section(SectionObserver* observer, std::string_view name, F&& f) {
  if (!observer) return std::forward<F>(f)();
  struct End {
    SectionObserver* observer;
    std::string_view name;
    ~End() { observer->end(name); }
  } end{observer, name};
  observer->begin(name);
  return std::forward<F>(f)();
}

}  // namespace corofem
