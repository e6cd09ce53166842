#include "cli/step_progress.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace corofem {

namespace {

/// "about 12 s left", "about 3 min left": the mean step so far times the steps left.
std::string time_left(double elapsed_s, int done, int steps) {
  const double left = elapsed_s / done * (steps - done);
  if (left < 90) return "about " + std::to_string(static_cast<int>(std::ceil(left))) + " s left";
  return "about " + std::to_string(static_cast<int>(std::ceil(left / 60))) + " min left";
}

}  // namespace

StepProgress::StepProgress(std::ostream* out, bool terminal, int steps, bool clocked)
    : out_(out),
      terminal_(terminal && clocked),
      clocked_(clocked),
      line_(out),
      steps_(steps),
      every_(std::max(1, steps / 10)),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void StepProgress::step_done(int step) {
  if (!out_ || steps_ <= 0) return;
  step = std::min(step, steps_);
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string counts = "corofem: step " + std::to_string(step) + "/" + std::to_string(steps_);
  if (terminal_) {
    // Redrawn at most five times a second, and at the last step.
    if (step < steps_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    constexpr int kWidth = 30;
    const int filled = kWidth * step / steps_;
    line_.draw(counts + " [" + std::string(filled, '#') + std::string(kWidth - filled, ' ') + "] " +
                   (step < steps_ ? time_left(elapsed, step, steps_) : std::string("done")),
               step == steps_);
    return;
  }
  if (step % every_ == 0 || step == steps_)
    *out_ << counts << (step < steps_ && clocked_ ? ", " + time_left(elapsed, step, steps_) : "")
          << "\n";
}

}  // namespace corofem
