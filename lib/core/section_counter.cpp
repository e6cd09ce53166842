#include "core/section_counter.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/allocator_calls.hpp"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define COROFEM_HAVE_CALLGRIND 1
#else
#define COROFEM_HAVE_CALLGRIND 0
#endif

namespace corofem {

namespace {

/// The label of a stretch outside every section, in callgrind's output (a dump's label cannot be
/// empty there).
constexpr const char* kOutside = "-";

/// callgrind's events, as its output's "events:" line names them.
struct CallgrindColumns {
  int ir = -1, d1mr = -1, d1mw = -1, dlmr = -1, dlmw = -1;
};

CallgrindColumns columns_of(const std::string& events_line) {
  std::istringstream in(events_line.substr(events_line.find(':') + 1));
  CallgrindColumns c;
  std::string name;
  for (int i = 0; in >> name; ++i) {
    if (name == "Ir") c.ir = i;
    if (name == "D1mr") c.d1mr = i;
    if (name == "D1mw") c.d1mw = i;
    if (name == "DLmr") c.dlmr = i;
    if (name == "DLmw") c.dlmw = i;
  }
  return c;
}

/// A "totals:" line's counts (callgrind leaves out trailing zero columns).
WorkCounts totals_of(const std::string& line, const CallgrindColumns& c) {
  std::istringstream in(line.substr(line.find(':') + 1));
  std::vector<std::uint64_t> v;
  std::uint64_t x;
  while (in >> x) v.push_back(x);
  const auto at = [&](int i) { return i >= 0 && i < static_cast<int>(v.size()) ? v[i] : 0; };
  return {at(c.ir), at(c.d1mr) + at(c.d1mw), at(c.dlmr) + at(c.dlmw)};
}

}  // namespace

SectionCounter::SectionCounter(CountSource source) : source_(source) {}

SectionCounter::~SectionCounter() {
#if COROFEM_HAVE_CALLGRIND
  if (source_ == CountSource::Callgrind && !finished_) CALLGRIND_STOP_INSTRUMENTATION;
#endif
}

std::unique_ptr<SectionCounter> SectionCounter::start(CountSource source, std::string& why_not,
                                                      const std::string& callgrind_file) {
  std::unique_ptr<SectionCounter> counter(new SectionCounter(source));
  if (source == CountSource::Reader) {
    why_not = "a reader's counts start with SectionCounter::reading";
    return nullptr;
  }
  if (source == CountSource::Perf) {
    counter->perf_ = PerfCounters::open(why_not);
    if (!counter->perf_) return nullptr;
    counter->read_ = [perf = &*counter->perf_] { return perf->read(); };
    counter->last_ = counter->read_();
    return counter;
  }
#if COROFEM_HAVE_CALLGRIND
  if (!RUNNING_ON_VALGRIND) {
    why_not =
        "callgrind counts need the run under valgrind --tool=callgrind --instr-atstart=no "
        "--combine-dumps=yes --cache-sim=yes (bench/count_phases.py runs it so)";
    return nullptr;
  }
  counter->callgrind_file_ =
      callgrind_file.empty() ? "callgrind.out." + std::to_string(::getpid()) : callgrind_file;
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_ZERO_STATS;
  return counter;
#else
  (void)callgrind_file;
  why_not = "this build has no valgrind/callgrind.h (Debian's valgrind package)";
  return nullptr;
#endif
}

std::unique_ptr<SectionCounter> SectionCounter::reading(std::function<WorkCounts()> read,
                                                        std::string tool) {
  std::unique_ptr<SectionCounter> counter(new SectionCounter(CountSource::Reader));
  counter->read_ = std::move(read);
  counter->tool_ = std::move(tool);
  counter->last_ = counter->read_();
  return counter;
}

int SectionCounter::path_index() {
  const auto [it, added] = path_indices_.try_emplace(path_, static_cast<int>(paths_.size()));
  if (added) paths_.push_back(path_);
  return it->second;
}

void SectionCounter::mark() {
  // Little work, and the same at every mark: it counts in the stretch it closes.
  ++marks_;
  const int index = path_index();
  if (read_) {
    const WorkCounts now = read_();
    exclusive_[paths_[index]] += now - last_;
    last_ = now;
    return;
  }
#if COROFEM_HAVE_CALLGRIND
  labels_.push_back(index);
  CALLGRIND_DUMP_STATS_AT(path_.empty() ? kOutside : path_.c_str());
#endif
}

void SectionCounter::begin(std::string_view section) {
  if (finished_) return;
  mark();
  open_.push_back(path_.size());
  if (!path_.empty()) path_ += '/';
  path_ += section;
}

void SectionCounter::end(std::string_view section) {
  if (finished_) return;
  mark();
  const std::size_t start = open_.empty() ? 0 : open_.back() + (open_.back() > 0 ? 1 : 0);
  if (open_.empty() || std::string_view(path_).substr(start) != section) {
    // Called from a destructor: no throw here; finish() says it.
    if (mismatch_.empty())
      mismatch_ = "section '" + std::string(section) + "' ended while '" + path_ + "' was open";
    return;
  }
  path_.resize(open_.back());
  open_.pop_back();
}

void SectionCounter::finish() {
  if (finished_) return;
  mark();
  finished_ = true;
  if (!mismatch_.empty()) throw std::logic_error("counted sections: " + mismatch_);
#if COROFEM_HAVE_CALLGRIND
  if (source_ == CountSource::Callgrind) {
    CALLGRIND_STOP_INSTRUMENTATION;
    read_callgrind_output();
  }
#endif
}

void SectionCounter::read_callgrind_output() {
  std::ifstream in(callgrind_file_);
  if (!in)
    throw std::runtime_error(callgrind_file_ +
                             ": callgrind's output cannot be read (valgrind must write it "
                             "there: --callgrind-out-file, and --combine-dumps=yes)");
  // Each dump is a part: "desc: Trigger: Client Request: LABEL", the events, then "totals:".
  // The allocator's calls in it are left out (core/allocator_calls.hpp).
  std::string line, label;
  CallgrindColumns columns;
  AllocatorCalls allocator;
  std::size_t dump = 0;
  const std::string trigger = "desc: Trigger: Client Request: ";
  while (std::getline(in, line)) {
    allocator.read(line);
    if (line.rfind("creator: ", 0) == 0) {
      tool_ = line.substr(9);
    } else if (line.rfind("desc: ", 0) == 0 && line.find(" cache: ") != std::string::npos) {
      const std::size_t colon = line.find(" cache: ");
      caches_[line.substr(6, colon - 6)] = line.substr(colon + 8);
    } else if (line.rfind(trigger, 0) == 0) {
      label = line.substr(trigger.size());
    } else if (line.rfind("events:", 0) == 0) {
      columns = columns_of(line);
    } else if (line.rfind("totals:", 0) == 0 && !label.empty()) {
      const std::string& path = dump < labels_.size() ? paths_[labels_[dump]] : label;
      if (dump >= labels_.size() || (path.empty() ? kOutside : path) != label)
        throw std::runtime_error(callgrind_file_ + ": dump " + std::to_string(dump + 1) +
                                 " is labelled '" + label +
                                 "', not this run's mark (another "
                                 "run's output, or one without --combine-dumps=yes)");
      const WorkCounts left_out = allocator.take();
      exclusive_[path] += totals_of(line, columns) - left_out;
      allocator_ += left_out;
      ++dump;
      label.clear();
    }
  }
  if (columns.ir < 0 || columns.d1mr < 0 || columns.dlmr < 0)
    throw std::runtime_error(callgrind_file_ +
                             ": callgrind counted no cache misses (run it with --cache-sim=yes)");
  allocator_left_out_ = allocator.seen();
  if (dump != labels_.size())
    throw std::runtime_error(callgrind_file_ + ": " + std::to_string(dump) + " dumps for " +
                             std::to_string(labels_.size()) + " marks (--combine-dumps=yes?)");
}

std::map<std::string, std::string> SectionCounter::event_definitions() const {
  if (source_ == CountSource::Reader)
    return {{"instructions", tool_}, {"d1_misses", tool_}, {"ll_misses", tool_}};
  if (source_ == CountSource::Perf)
    return {{"instructions", "instructions (user space)"},
            {"d1_misses", "L1-dcache-load-misses"},
            {"ll_misses", "LLC-load-misses"}};
  const std::string outside = allocator_left_out_ ? ", outside the C library's allocator" : "";
  return {{"instructions", "Ir" + outside},
          {"d1_misses", "D1mr + D1mw (simulated)" + outside},
          {"ll_misses", "DLmr + DLmw (simulated)" + outside}};
}

std::map<std::string, WorkCounts> inclusive(const std::map<std::string, WorkCounts>& exclusive) {
  std::map<std::string, WorkCounts> out;
  for (const auto& [path, counts] : exclusive) {
    if (path.empty()) continue;
    for (std::size_t slash = path.find('/'); slash != std::string::npos;
         slash = path.find('/', slash + 1))
      out[path.substr(0, slash)] += counts;
    out[path] += counts;
  }
  return out;
}

}  // namespace corofem
