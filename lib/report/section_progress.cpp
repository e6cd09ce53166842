#include "report/section_progress.hpp"

#include <cmath>

#include "core/number_text.hpp"

namespace corofem {

SectionProgress::SectionProgress(std::ostream* out, std::string section, int units,
                                 std::string tool)
    : out_(out), section_(std::move(section)), tool_(std::move(tool)), units_(units) {}

std::string SectionProgress::begin(const std::string& unit) {
  const std::lock_guard<std::mutex> hold(lock_);
  std::string prefix = tool_ + ": " + section_ + " " + std::to_string(++started_) + "/" +
                       std::to_string(units_) + ": " + unit;
  if (done_ > 0) {
    const double elapsed_min =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() / 60;
    prefix += " (about " + general_number(std::ceil(elapsed_min / done_ * (units_ - done_))) +
              " min left)";
  }
  return prefix;
}

void SectionProgress::finish() {
  const std::lock_guard<std::mutex> hold(lock_);
  ++done_;
}

}  // namespace corofem
