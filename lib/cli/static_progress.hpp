#pragma once
// Progress of a static run's load increments and iterations on stderr: on a terminal one line
// redrawn in place; otherwise (a log file, CI) a line for each tenth of the increments and, while
// one increment takes long, one every few seconds with its residual.
#include <chrono>
#include <ostream>

#include "integrate/static_solver.hpp"

namespace corofem {

class StaticProgress {
 public:
  /// `out` null: silent. `terminal`: out is a terminal (redraw in place). `tolerance`: the
  /// residual the increments iterate to.
  StaticProgress(std::ostream* out, bool terminal, double tolerance);
  void iteration_done(const StaticIteration& at);

 private:
  std::ostream* out_;
  bool terminal_;
  double tolerance_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace corofem
