#pragma once
// `corofem compare`'s verdicts: rows of two record sets paired by what was run, each timed row
// tested (shift_test.hpp), each counter compared exactly, each accuracy field against a stated
// tolerance.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/record_rows.hpp"
#include "compare/shift_test.hpp"

namespace corofem {

struct CompareOptions {
  double threshold = 0.05;  ///< a timing verdict needs NEW/BASE beyond 1 +- this (and p < alpha)
  /// The chance of any false timing verdict among the gated rows (family-wise, Holm); the
  /// intervals are each at 1 - alpha.
  double alpha = 0.01;
  /// An accuracy field (an error against an oracle, a residual) regresses when it grows by more
  /// than this factor and past accuracy_floor: iterative solves move their error within their
  /// tolerance when operations are reordered, so a doubling is the signal, not a change.
  double accuracy_factor = 2;
  double accuracy_floor = 1e-12;  ///< errors below this are rounding, never a regression
  /// The two runs' final displacements: |u_new - u_base| / |u_base| above this is a regression.
  /// The same code gives the same bits at every thread count (0); energy-newton's rotations off
  /// by 1e-6 rad move the gate suite's fields by 0.9-3.6e-7 (bench/gate/plant.py), found 10x over.
  double field_tolerance = 1e-8;
  double min_ms = 0.05;  ///< timed rows whose BASE median is shorter are shown, not gated
  /// A timed row too short of runs to be tested whose ratio is beyond this factor either way is
  /// suspect, not passed (a slower one fails the comparison): one repetition of a 100x slowdown
  /// is not "no regression".
  double suspect_factor = 2;
  /// Compare only the cases both sides ran on the same scenes (a report against a snapshot of
  /// other scenes): the others are summarized in `unpaired`, neither rows nor regressions.
  bool paired_only = false;
  /// A phase's instructions (callgrind or perf counts) are "more" or "fewer" when they move by
  /// more than this, relative; its D1 and LL misses by more than miss_threshold. Counted twice,
  /// one binary's counts are equal; what they move by when unrelated code shifts the heap's
  /// layout sets these (lib/docs/comparing.md, "Counted phases").
  double count_threshold = 0.005;
  double miss_threshold = 0.05;
  double min_count = 20000;  ///< count rows whose BASE is smaller are shown, not gated
};

struct RowComparison {
  std::string case_name, quantity;
  int threads = 0;
  RowKind kind = RowKind::Timed;
  /// faster, slower, same, inconclusive (too few samples), suspect (too few samples and a ratio
  /// beyond suspect_factor), short (under min_ms); for counters
  /// equal, increased, decreased; for accuracy better, worse, within tolerance; for fields equal,
  /// within tolerance, changed; for work counts equal, within threshold, more, fewer, not compared
  /// (counted otherwise); missing in new, new row.
  std::string verdict;
  bool regression = false;
  double base_value = 0, new_value = 0;  ///< medians (timed), values (counters, accuracy), |du|/|u|
  ShiftTest test;                        ///< timed rows
  /// Timed rows: the test's p adjusted for the family of gated rows (Holm); the verdict's p.
  double p_adjusted = 1;
  std::string unit_of_sample;  ///< "runs" (medians of >= 3 runs each side) or "steps" (pooled)
  std::string note;
  /// Timed rows whose case (or, for `all cases`, any case) also has counts of the phase on both
  /// sides: "code" where the counts moved beyond their threshold, "machine" where none did (the
  /// timing moved with the same work: placement, noise); empty without counts.
  std::string attribution;
  std::string attribution_note;  ///< the largest count change behind it, e.g. "instructions +3.1%"
};

struct Comparison {
  CompareOptions options;
  std::vector<RowComparison> rows;
  std::vector<std::string> warnings;  ///< machine, compiler or flags that differ
  /// paired_only: the cases left out, one line for each reason (only one side ran them, or ran
  /// them on other scenes), naming a few.
  std::vector<std::string> unpaired;
  nlohmann::json base_context, new_context;
  bool regressed() const;
  /// Timed rows that could not be tested (too few runs a side), and the runs a side that would
  /// test every timed row at alpha after Holm's adjustment (0 where none is untested).
  int untested() const;
  int runs_to_decide() const;
  /// REGRESSION, inconclusive (nothing regressed, but timed rows went untested), or no
  /// regression.
  std::string headline() const;
  /// Work counts that fell beyond their threshold: the baseline they were compared with is stale.
  bool counts_fell() const;
};

/// Pairs the rows by key. Throws InputError where a case of both sides was run on different
/// scenes (naming both rows), or where no row pairs at all.
Comparison compare_records(const RecordSet& base, const RecordSet& contender,
                           const CompareOptions& options);

}  // namespace corofem
