#include "core/event_log.hpp"

namespace corofem {

void EventLog::begin(std::string_view section) {
  const Clock::time_point now = Clock::now();
  const std::lock_guard lock(mutex_);
  open_[std::this_thread::get_id()].push_back({std::string(section), now});
}

void EventLog::end(std::string_view section) {
  const Clock::time_point now = Clock::now();
  const std::lock_guard lock(mutex_);
  std::vector<Open>& open = open_[std::this_thread::get_id()];
  // in_section ends what it began, in order, even through an exception; a section ended by hand
  // out of order closes the ones opened inside it, unrecorded.
  while (!open.empty() && open.back().name != section) open.pop_back();
  if (open.empty()) return;
  ms_[open.back().name] +=
      std::chrono::duration<double, std::milli>(now - open.back().start).count();
  open.pop_back();
}

void EventLog::event(std::string_view name) {
  const std::lock_guard lock(mutex_);
  const auto it = counts_.find(name);
  if (it == counts_.end())
    counts_.emplace(std::string(name), 1);
  else
    ++it->second;
}

void EventLog::iterated(std::string_view solver, int /*iteration*/, double residual) {
  const std::lock_guard lock(mutex_);
  const auto it = history_.find(solver);
  if (it == history_.end())
    history_.emplace(std::string(solver), std::vector<double>{residual});
  else
    it->second.push_back(residual);
}

void EventLog::solved(std::string_view solver, int iterations, double residual, double rate) {
  const std::lock_guard lock(mutex_);
  std::vector<double> residuals;
  if (const auto it = history_.find(solver); it != history_.end()) residuals.swap(it->second);
  solves_.push_back({std::string(solver), iterations, residual, rate, std::move(residuals)});
}

double EventLog::ms(std::string_view name) const {
  const std::lock_guard lock(mutex_);
  const auto it = ms_.find(name);
  return it == ms_.end() ? 0.0 : it->second;
}

int EventLog::count(std::string_view name) const {
  const std::lock_guard lock(mutex_);
  const auto it = counts_.find(name);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace corofem
