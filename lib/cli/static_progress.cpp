#include "cli/static_progress.hpp"

#include <algorithm>
#include <string>

#include "core/number_text.hpp"

namespace corofem {

namespace {

/// A line on a log file while one increment iterates, at most this often.
constexpr auto kLogEvery = std::chrono::seconds(5);
/// A redraw on a terminal, at most this often.
constexpr auto kRedrawEvery = std::chrono::milliseconds(200);

std::string increment_text(const StaticIteration& at) {
  return "corofem: " + at.name();
}

}  // namespace

StaticProgress::StaticProgress(std::ostream* out, bool terminal, double tolerance)
    : out_(out),
      terminal_(terminal),
      tolerance_(tolerance),
      line_(out),
      last_draw_(std::chrono::steady_clock::now()) {}

void StaticProgress::iteration_done(const StaticIteration& at) {
  if (!out_) return;
  const auto now = std::chrono::steady_clock::now();
  const std::string residual =
      "residual " + general_number(at.residual) + " (to " + general_number(tolerance_) + ")";
  const std::string text =
      at.converged
          ? increment_text(at) + " converged in " + std::to_string(at.iteration) + " iterations"
      : at.cut
          ? increment_text(at) + " missed the tolerance after " + std::to_string(at.iteration) +
                " iterations, " + residual + ": halved"
          : increment_text(at) + ", iteration " + std::to_string(at.iteration) + ": " + residual;
  const bool settled = at.converged || at.cut;  // an increment's end, always shown
  if (terminal_) {
    if (!settled && now - last_draw_ < kRedrawEvery) return;
    last_draw_ = now;
    line_.draw(text, at.cut || (at.converged && at.increment == at.increments));
    return;
  }
  const long long every = std::max(1LL, at.increments / 10);
  const bool tenth = at.converged && (at.increment % every == 0 || at.increment == at.increments);
  if (tenth || at.cut || (!settled && now - last_draw_ >= kLogEvery)) {
    last_draw_ = now;
    *out_ << text << "\n";
  }
}

}  // namespace corofem
