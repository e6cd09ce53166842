#include "io/phase_counts_record.hpp"

namespace corofem {

namespace {

nlohmann::json to_json(const WorkCounts& c) {
  return {{"instructions", c.instructions}, {"d1_misses", c.d1_misses}, {"ll_misses", c.ll_misses}};
}

}  // namespace

nlohmann::json to_json(const SectionCounter& counter, int threads) {
  nlohmann::json sections = nlohmann::json::object();
  for (const auto& [path, counts] : inclusive(counter.exclusive()))
    sections[path] = to_json(counts);
  const auto outside = counter.exclusive().find("");
  nlohmann::json r = {
      {"source", kCountSources.name(counter.source())},
      {"tool", counter.tool()},
      {"events", counter.event_definitions()},
      {"threads", threads},
      {"processor_seen", processor_seen()},
      {"marks", counter.marks()},
      {"sections", std::move(sections)},
      {"outside", to_json(outside != counter.exclusive().end() ? outside->second : WorkCounts{})}};
  if (counter.source() == CountSource::Callgrind) {
    r["simulated_caches"] = counter.simulated_caches();
    r["allocator_left_out"] = to_json(counter.allocator_left_out());
  }
  if (counter.source() == CountSource::Perf && threads > 1)
    r["note"] = "perf counts the calling thread alone: the other threads' work is not in them";
  return r;
}

nlohmann::json unavailable_counts(CountSource asked, const std::string& why_not) {
  return {{"source", nullptr}, {"asked", kCountSources.name(asked)}, {"unavailable", why_not}};
}

}  // namespace corofem
