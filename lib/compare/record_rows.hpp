#pragma once
// The rows `corofem compare` pairs, read from what corofem writes: run records (`corofem run`),
// report folders (tables.json, speed_accuracy.json, cache_profile.json), the counted runs of
// bench/count_phases.py (a bundle of run records) and Google Benchmark JSON
// (corofem_bench --benchmark_out). A folder of several records of the same cases (ci/bench-gate's
// repetitions) gives each row one run per record.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace corofem {

enum class RowKind {
  Timed,     ///< milliseconds that wobble: samples per run
  Counter,   ///< a cost that does not wobble (iterations, bytes, flops, nonzeros, cache misses)
  Accuracy,  ///< an error against an oracle or a residual: smaller is better
  Field,     ///< the final displacements, compared between the two sides
  Count,     ///< a phase's instructions or cache misses (core/section_counter.hpp): a threshold
};

/// One quantity of one case, e.g. the solve phase of Table 1's bunny at 2 threads.
struct RecordRow {
  std::string case_name;     ///< what was run ("run cantilever.json", "table1 bunny-11k")
  std::string scene_digest;  ///< the scene's content; a case pairs only with an equal digest
  int threads = 0;
  std::string quantity;  ///< phase or field name
  RowKind kind = RowKind::Timed;
  std::vector<std::vector<double>> runs;  ///< Timed: per run (record), its samples in ms
  std::vector<double> values;             ///< Counter, Accuracy: per run
  std::vector<double> field;              ///< Field: the first run's values
  std::string source;                     ///< file and row, for messages
  /// Count: what counted and what it counted (source, tool, simulated caches, the processor the
  /// code saw, compiler, flags, block kernels), as canonical JSON: counts compare only with
  /// counts made alike.
  std::string provenance;

  /// What pairs it: case, threads and quantity.
  std::string key() const;
};

struct RecordSet {
  std::vector<RecordRow> rows;
  /// Per file read: its "context" (commit, compiler, flags, machine), null where it has none.
  std::map<std::string, nlohmann::json> contexts;
};

/// Reads a record file or a folder of them. Throws InputError naming the file (and the row) when a
/// file cannot be read, is no record corofem compare knows, or holds a malformed row.
RecordSet read_records(const std::filesystem::path& path);

/// The rows of one parsed record (`file` names it in messages); appends to `set`.
void add_record_rows(const nlohmann::json& record, const std::string& file, RecordSet& set);

}  // namespace corofem
