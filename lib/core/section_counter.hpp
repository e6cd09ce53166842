#pragma once
// Counts the work of every section a run marks (core/event_observer.hpp): instructions, D1 and
// last-level misses per phase of a step and per part of a solver. The work between two
// consecutive marks belongs to the innermost open section, named by its path ("update/galerkin";
// "" outside every section), so each count is exclusive of the sections nested in it;
// inclusive() sums a path's own count and its children's.
//
// Two sources:
// - perf: the hardware's counters, read in-process at each mark (core/work_counts.hpp); where the
//   machine has none, start() says why and nothing is counted.
// - callgrind: each mark asks valgrind's callgrind for its counts since the previous mark
//   (CALLGRIND_DUMP_STATS_AT, labelled with the path), on its simulated caches, so the counts are
//   exact, repeatable and the same on any host with the same binary; finish() reads them back from
//   callgrind's output file. The process must run under
//     valgrind --tool=callgrind --instr-atstart=no --combine-dumps=yes --cache-sim=yes
//   (bench/count_phases.py does): counting starts with start(), not with the process, so the
//   set-up's meshing does not pay for the cache simulation.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/event_observer.hpp"
#include "core/name_table.hpp"
#include "core/work_counts.hpp"

namespace corofem {

/// Reader: counts a caller reads itself (SectionCounter::reading: counters of one's own, tests).
enum class CountSource { Perf, Callgrind, Reader };
inline constexpr NameTable<CountSource, 3> kCountSources{{{{CountSource::Perf, "perf"},
                                                           {CountSource::Callgrind, "callgrind"},
                                                           {CountSource::Reader, "reader"}}}};

class SectionCounter : public EventObserver {
 public:
  /// Starts counting from `source`; nothing (and `why_not` says why) where it cannot: no hardware
  /// counters, or callgrind asked for outside valgrind. `callgrind_file`: the output file given to
  /// valgrind (--callgrind-out-file); empty for its default, callgrind.out.<pid>.
  static std::unique_ptr<SectionCounter> start(CountSource source, std::string& why_not,
                                               const std::string& callgrind_file = {});
  /// Counts read in-process from `read` at each mark (the counts since any fixed start); `tool`
  /// names it in the record.
  static std::unique_ptr<SectionCounter> reading(std::function<WorkCounts()> read,
                                                 std::string tool);
  ~SectionCounter() override;

  void begin(std::string_view section) override;
  void end(std::string_view section) override;
  /// Counts the last stretch and stops; callgrind: reads the counts back (std::runtime_error
  /// naming the file when its output cannot be read or does not match the marks;
  /// std::logic_error when a section ended out of order).
  void finish();

  CountSource source() const { return source_; }
  /// The events as this source defines them ("instructions": "Ir", ...), for the record.
  std::map<std::string, std::string> event_definitions() const;
  /// callgrind: its simulated caches as it reports them ("D1": "32768 B, 64 B, 8-way
  /// associative"); empty for perf.
  const std::map<std::string, std::string>& simulated_caches() const { return caches_; }
  /// What counted: "perf_event_open", or callgrind's output's creator ("callgrind-3.19.0").
  const std::string& tool() const { return tool_; }
  /// After finish(): each section path's own counts ("" outside every section).
  const std::map<std::string, WorkCounts>& exclusive() const { return exclusive_; }
  int marks() const { return marks_; }
  /// callgrind: the C library's allocator's counts, left out of every section's
  /// (core/allocator_calls.hpp); zero where its functions were not found by name.
  const WorkCounts& allocator_left_out() const { return allocator_; }

 private:
  explicit SectionCounter(CountSource source);
  void mark();       ///< the stretch since the last mark, to the path open now
  int path_index();  ///< the open path's number in paths_ (added at its first mark)
  void read_callgrind_output();

  CountSource source_;
  std::optional<PerfCounters> perf_;
  std::function<WorkCounts()> read_;  ///< perf and reader: the counts now
  WorkCounts last_{};
  std::string path_;               ///< the open sections, "update/galerkin"
  std::vector<std::size_t> open_;  ///< path_'s length before each open section
  std::vector<std::string> paths_;
  std::map<std::string, int> path_indices_;
  std::vector<int> labels_;  ///< callgrind: each dump's path, in order
  std::map<std::string, WorkCounts> exclusive_;
  WorkCounts allocator_{};
  bool allocator_left_out_ = false;
  std::map<std::string, std::string> caches_;
  std::string callgrind_file_;
  std::string tool_ = "perf_event_open";
  std::string mismatch_;  ///< a section that ended out of order: finish() says so
  int marks_ = 0;
  bool finished_ = false;
};

/// Every path's inclusive counts: its own and those of the paths nested in it ("update" holds
/// "update/galerkin"); the stretches outside every section are left out.
std::map<std::string, WorkCounts> inclusive(const std::map<std::string, WorkCounts>& exclusive);

}  // namespace corofem
