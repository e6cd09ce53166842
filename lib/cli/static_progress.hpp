#pragma once
// Progress of a static run's load increments and iterations on stderr: on a terminal one line
// redrawn in place; otherwise (a log file, CI) a line for each tenth of the increments and, while
// one increment takes long, one every few seconds with its residual.
#include <chrono>
#include <ostream>

#include "cli/redrawn_line.hpp"
#include "integrate/static_solver.hpp"

namespace corofem {

class StaticProgress {
 public:
  /// `out` null: silent. `terminal`: out is a terminal (redraw in place). `tolerance`: the
  /// residual the increments iterate to.
  StaticProgress(std::ostream* out, bool terminal, double tolerance);
  void iteration_done(const StaticIteration& at);
  /// Ends the terminal's line if a redraw left it open (a run that stops early).
  void end_line() { line_.end(); }

 private:
  std::ostream* out_;
  bool terminal_;
  double tolerance_;
  RedrawnLine line_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace corofem
