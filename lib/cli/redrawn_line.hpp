#pragma once
// One line of progress on a terminal, redrawn in place, and ended before anything else is written
// (a run that stops early, an error message): otherwise the next output joins the open line.
#include <ostream>
#include <string>

namespace corofem {

class RedrawnLine {
 public:
  explicit RedrawnLine(std::ostream* out) : out_(out) {}
  RedrawnLine(const RedrawnLine&) = delete;
  RedrawnLine& operator=(const RedrawnLine&) = delete;
  ~RedrawnLine() { end(); }

  /// Draws `text` over the line; `keep`: ends the line after it.
  void draw(const std::string& text, bool keep) {
    *out_ << "\r" << text << "\x1b[K" << (keep ? "\n" : "") << std::flush;
    open_ = !keep;
  }
  /// Ends a line left open by a draw.
  void end() {
    if (!open_) return;
    *out_ << "\n" << std::flush;
    open_ = false;
  }

 private:
  std::ostream* out_;
  bool open_ = false;
};

}  // namespace corofem
