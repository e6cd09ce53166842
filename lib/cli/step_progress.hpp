#pragma once
// Progress of a run's steps on stderr: on a terminal one line redrawn in place, a bar with the
// time left; otherwise (a log file, CI) a line every tenth of the run, with the time left.
#include <chrono>
#include <ostream>

#include "cli/redrawn_line.hpp"

namespace corofem {

class StepProgress {
 public:
  /// `out` null: silent. `terminal`: out is a terminal (redraw in place). `clocked` false: a line
  /// every tenth of the run without the time left, on a terminal too (a counted run: lines whose
  /// length and number follow the clock would move the heap's layout, and so the counts).
  StepProgress(std::ostream* out, bool terminal, int steps, bool clocked = true);
  /// After step `step` (1-based) of the run.
  void step_done(int step);
  /// Ends the terminal's line if a redraw left it open (a run that stops early).
  void end_line() { line_.end(); }

 private:
  std::ostream* out_;
  bool terminal_;
  bool clocked_;
  RedrawnLine line_;
  int steps_, every_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace corofem
