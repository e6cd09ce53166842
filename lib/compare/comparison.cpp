#include "compare/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/statistics.hpp"

namespace corofem {
namespace {

/// The samples a timed row is tested on: with at least 3 runs (records) on each side, one median
/// per run, since steps of one run share its machine state and are not independent of each
/// other; with fewer, the steps pooled (noted: run-to-run noise is then not sampled).
std::vector<double> test_samples(const RecordRow& row, bool per_run) {
  std::vector<double> out;
  for (const auto& run : row.runs) {
    if (per_run)
      out.push_back(median(run));
    else
      out.insert(out.end(), run.begin(), run.end());
  }
  return out;
}

/// The smallest two-sided p the U test can give for n against m (complete separation).
double smallest_p(int n, int m) {
  double arrangements = 1;  // C(n+m, n)
  for (int i = 1; i <= n; ++i) arrangements = arrangements * (m + i) / i;
  return std::min(1.0, 2 / arrangements);
}

RowComparison timed(const RecordRow& b, const RecordRow& n, const CompareOptions& o) {
  RowComparison c;
  const bool per_run = b.runs.size() >= 3 && n.runs.size() >= 3;
  const auto one_sample = [](const RecordRow& r) {
    return std::all_of(r.runs.begin(), r.runs.end(),
                       [](const auto& run) { return run.size() == 1; });
  };
  c.unit_of_sample = per_run || (one_sample(b) && one_sample(n)) ? "runs" : "steps";
  const std::vector<double> xs = test_samples(b, per_run), ys = test_samples(n, per_run);
  c.base_value = median(test_samples(b, false));
  c.new_value = median(test_samples(n, false));
  c.test = shift_test(xs, ys, o.alpha);
  c.p_adjusted = c.test.p_value;
  if (c.unit_of_sample == "steps")
    c.note = "fewer than 3 runs a side: steps pooled, run-to-run noise not sampled";
  if (smallest_p(c.test.base_count, c.test.new_count) >= o.alpha) {
    const bool beyond = c.test.ratio > o.suspect_factor || c.test.ratio < 1 / o.suspect_factor;
    c.verdict = beyond ? "suspect" : "inconclusive";
    c.regression = beyond && c.test.ratio > 1;
    if (beyond)
      c.note = "too few runs to test, and " + general_number(c.test.ratio) + "x: rerun with more";
  } else if (c.base_value < o.min_ms)
    c.note += std::string(c.note.empty() ? "" : "; ") + "under --min-ms: shown, not gated";
  // Else gated: the verdict waits for the family's adjusted p (holm_verdicts).
  return c;
}

/// The gated timed rows are one family of tests: a gate over 80 rows at alpha = 0.01 each would
/// alarm on half of its A/A runs. Holm's step-down procedure (Holm 1979) holds the chance of any
/// false "slower" or "faster" among them at alpha, and is uniformly more powerful than Bonferroni:
/// the i-th smallest p is multiplied by (m - i + 1), the products made monotone. Rows under
/// --min-ms, and those whose samples cannot reach alpha, are left out of the family.
void holm_verdicts(std::vector<RowComparison>& rows, const CompareOptions& o) {
  std::vector<RowComparison*> family;
  for (RowComparison& r : rows)
    if (r.kind == RowKind::Timed && !r.unit_of_sample.empty() && r.verdict != "inconclusive" &&
        r.verdict != "suspect")
      family.push_back(&r);
  std::sort(family.begin(), family.end(), [](const RowComparison* a, const RowComparison* b) {
    return a->test.p_value < b->test.p_value;
  });
  std::vector<RowComparison*> gated;
  for (RowComparison* r : family)
    if (r->note.find("not gated") == std::string::npos) gated.push_back(r);
  double running = 0;
  const double m = static_cast<double>(gated.size());
  for (std::size_t i = 0; i < gated.size(); ++i) {
    running =
        std::max(running, std::min(1.0, (m - static_cast<double>(i)) * gated[i]->test.p_value));
    gated[i]->p_adjusted = running;
  }
  for (RowComparison* r : family) {
    const bool significant = r->p_adjusted < o.alpha;
    if (significant && r->test.ratio > 1 + o.threshold)
      r->verdict = "slower";
    else if (significant && r->test.ratio < 1 / (1 + o.threshold))
      r->verdict = "faster";
    else
      r->verdict = "same";
    if (r->verdict == "slower" && r->note.find("not gated") != std::string::npos)
      r->verdict = "short";
    r->regression = r->verdict == "slower";
  }
}

RowComparison counter(const RecordRow& b, const RecordRow& n) {
  RowComparison c;
  c.base_value = median(b.values);
  c.new_value = median(n.values);
  for (const RecordRow* side : {&b, &n})
    if (std::any_of(side->values.begin(), side->values.end(),
                    [&](double v) { return v != side->values.front(); }))
      c.note = "varies between the runs of one side";
  // Every counter recorded is a cost (iterations, bytes, flops, vertices, misses): more is worse.
  c.verdict = c.new_value > c.base_value   ? "increased"
              : c.new_value < c.base_value ? "decreased"
                                           : "equal";
  c.regression = c.verdict == "increased";
  return c;
}

/// A phase's work counted on both sides: exact, so a threshold and no test; what moves it without a
/// change to the phase's code (the heap's layout shifted by other code) sets the threshold.
RowComparison work_count(const RecordRow& b, const RecordRow& n, const CompareOptions& o) {
  RowComparison c;
  c.base_value = median(b.values);
  c.new_value = median(n.values);
  if (b.provenance != n.provenance) {
    c.verdict = "not compared";
    c.note = "counted otherwise (see the warnings)";
    return c;
  }
  const bool misses = b.quantity.size() > 7 && b.quantity.ends_with(" misses");
  const double limit = misses ? o.miss_threshold : o.count_threshold;
  const double growth = c.base_value > 0  ? c.new_value / c.base_value - 1
                        : c.new_value > 0 ? INFINITY
                                          : 0.0;
  c.test.ratio = 1 + growth;
  c.verdict = c.new_value == c.base_value ? "equal"
              : growth > limit            ? "more"
              : growth < -limit           ? "fewer"
                                          : "within threshold";
  const bool moved = c.verdict == "more" || c.verdict == "fewer";
  // A solver part's misses depend on what the part before it left in the caches, and the heap's
  // layout moves misses between neighbouring parts (the 11k quadruped's fine transfer: -5.9% in
  // LL misses when only the source folder's path changed, its phase -0.7%): its phase's misses
  // are gated, the part's shown. Instructions do not move so, and are gated in every part.
  const bool part = b.quantity.substr(0, b.quantity.find(' ')).find('/') != std::string::npos;
  if (moved && c.base_value < o.min_count) {
    c.note = "under --min-count: shown, not gated";
  } else if (moved && misses && part) {
    c.note = "a part's misses: shown, not gated (its phase's are)";
  } else {
    c.regression = c.verdict == "more";
    if (c.verdict == "fewer") c.note = "the baseline is stale: refresh it";
  }
  return c;
}

RowComparison accuracy(const RecordRow& b, const RecordRow& n, const CompareOptions& o) {
  RowComparison c;
  c.base_value = *std::max_element(b.values.begin(), b.values.end());
  c.new_value = *std::max_element(n.values.begin(), n.values.end());
  if (!std::isfinite(c.new_value) ||
      (c.new_value > c.base_value * o.accuracy_factor && c.new_value > o.accuracy_floor))
    c.verdict = "worse";
  else if (c.new_value * o.accuracy_factor < c.base_value && c.base_value > o.accuracy_floor)
    c.verdict = "better";
  else
    c.verdict = "within tolerance";
  c.regression = c.verdict == "worse";
  return c;
}

RowComparison field(const RecordRow& b, const RecordRow& n, const CompareOptions& o) {
  RowComparison c;
  if (b.field.size() != n.field.size()) {
    c.verdict = "changed";
    c.note = "sizes differ: " + std::to_string(b.field.size()) + " against " +
             std::to_string(n.field.size());
    c.regression = true;
    return c;
  }
  double diff = 0, norm = 0;
  bool finite = true;
  for (std::size_t i = 0; i < b.field.size(); ++i) {
    finite &= std::isfinite(n.field[i]);
    diff += (n.field[i] - b.field[i]) * (n.field[i] - b.field[i]);
    norm += b.field[i] * b.field[i];
  }
  c.new_value = !finite ? NAN : norm > 0 ? std::sqrt(diff / norm) : std::sqrt(diff);
  c.verdict = !finite                            ? "changed"
              : c.new_value == 0                 ? "equal"
              : c.new_value <= o.field_tolerance ? "within tolerance"
                                                 : "changed";
  if (!finite) c.note = "NEW holds values that are not finite";
  c.regression = c.verdict == "changed";
  return c;
}

/// "+3.1%" without the sign: a relative change in percent, to 2 significant digits past 1%.
std::string fixed_percent(double change) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g%%", 100 * change);
  return text;
}

/// Handoff times this many times apart are two placements of the cores (lib/docs/threads.md,
/// "Where the host puts the two cores": one VM's two measured 49-72 and 192-310 ns).
constexpr double kPlacementRatio = 2.0;

/// Every record's context[key] in `set`, where it has one.
std::vector<nlohmann::json> context_fields(const RecordSet& set, const char* key) {
  std::vector<nlohmann::json> out;
  for (const auto& [file, context] : set.contexts)
    if (context.is_object() && context.contains(key)) out.push_back(context[key]);
  return out;
}

/// Warnings where the two sides were produced differently.
std::vector<std::string> context_warnings(const RecordSet& base, const RecordSet& contender) {
  // Distinct, as text, in order; a record that left the field empty (a profile that did not
  // read the CPU) says nothing of it.
  auto values = [](const RecordSet& set, const char* key) {
    std::vector<std::string> out;
    for (const nlohmann::json& field : context_fields(set, key)) {
      const std::string v = field.is_string() ? field.get<std::string>() : field.dump();
      if (!v.empty() && v != "null" && std::find(out.begin(), out.end(), v) == out.end())
        out.push_back(v);
    }
    return out;
  };
  auto joined = [](const std::vector<std::string>& v) {
    std::string out;
    for (const std::string& s : v) out += (out.empty() ? "" : " and ") + s;
    return out;
  };
  std::vector<std::string> warnings;
  for (const char* key : {"cpu", "host", "compiler", "flags", "build_type", "block_kernels"}) {
    const std::vector<std::string> b = values(base, key), n = values(contender, key);
    if (!b.empty() && !n.empty() && b != n)
      warnings.push_back(std::string(key) + " differs: BASE " + joined(b) + ", NEW " + joined(n) +
                         " (timings compare the machines as much as the code)");
  }
  // Two-thread timings move with where the host put the two cores (core/core_latency.hpp): a
  // handoff time twice as long on one side is a different machine for them.
  auto handoff_ns = [](const RecordSet& set) {  // null at one thread: left out
    std::vector<double> out;
    for (const nlohmann::json& field : context_fields(set, "core_to_core_ns"))
      if (field.is_number()) out.push_back(field.get<double>());
    return out;
  };
  const std::vector<double> b = handoff_ns(base), n = handoff_ns(contender);
  if (!b.empty() && !n.empty()) {
    const double base_ns = median(b), new_ns = median(n);
    if (std::max(base_ns, new_ns) > kPlacementRatio * std::min(base_ns, new_ns))
      warnings.push_back("core_to_core_ns differs: BASE " + general_number(std::round(base_ns)) +
                         " ns, NEW " + general_number(std::round(new_ns)) + " ns" +
                         " (the host placed the two cores apart differently: two-thread timings "
                         "compare the placements as much as the code)");
  }
  return warnings;
}

/// Where one side's counts were made otherwise than the other's (another compiler, flags, tool,
/// simulated caches or processor seen): what differs, once. Their count rows are not compared;
/// the counters (iterations, the hierarchy's sizes) still are.
std::string provenance_warning(const RecordSet& base, const RecordSet& contender) {
  std::map<std::string, const RecordRow*> counted;
  for (const RecordRow& r : contender.rows)
    if (r.kind == RowKind::Count) counted.emplace(r.key(), &r);
  for (const RecordRow& b : base.rows) {
    const auto it = b.kind == RowKind::Count ? counted.find(b.key()) : counted.end();
    if (it == counted.end() || it->second->provenance == b.provenance) continue;
    const nlohmann::json x = nlohmann::json::parse(b.provenance),
                         y = nlohmann::json::parse(it->second->provenance);
    std::string what;
    for (const auto& [key, value] : x.items())
      if (!y.contains(key) || y[key] != value)
        what += (what.empty() ? "" : "; ") + key + ": BASE " + value.dump() + ", NEW " +
                (y.contains(key) ? y[key].dump() : std::string("none"));
    return "work counts made otherwise (" + what +
           "): instruction and miss counts are not compared; iterations and the hierarchy's "
           "sizes still are";
  }
  return {};
}

nlohmann::json first_context(const RecordSet& set) {
  for (const auto& [file, context] : set.contexts)
    if (context.is_object()) return context;
  return nullptr;
}

}  // namespace

bool Comparison::regressed() const {
  return std::any_of(rows.begin(), rows.end(), [](const RowComparison& r) { return r.regression; });
}

int Comparison::untested() const {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(), [](const RowComparison& r) {
    return r.kind == RowKind::Timed && (r.verdict == "inconclusive" || r.verdict == "suspect");
  }));
}

int Comparison::runs_to_decide() const {
  if (untested() == 0) return 0;
  const auto timed = std::count_if(rows.begin(), rows.end(), [](const RowComparison& r) {
    return r.kind == RowKind::Timed && r.case_name != "all cases";
  });
  // Complete separation of n against n is the strongest evidence n runs can give: 2 / C(2n, n),
  // which Holm's first step multiplies by the rows gated.
  for (int n = 2; n <= 100; ++n)
    if (smallest_p(n, n) * static_cast<double>(timed) < options.alpha) return n;
  return 100;
}

std::string Comparison::headline() const {
  return regressed() ? "REGRESSION" : untested() > 0 ? "inconclusive" : "no regression";
}

bool Comparison::counts_fell() const {
  return std::any_of(rows.begin(), rows.end(), [](const RowComparison& r) {
    return r.kind == RowKind::Count && r.verdict == "fewer" &&
           r.note.find("not gated") == std::string::npos;
  });
}

namespace {

/// A case both sides ran must be the same scene on both: else its rows say nothing of the code.
/// Refused (InputError naming both rows), or with paired_only returned, to be left out.
std::set<std::string> different_scenes(const RecordSet& base, const RecordSet& contender,
                                       bool paired_only) {
  std::map<std::string, const RecordRow*> new_cases;
  for (const RecordRow& r : contender.rows) new_cases.emplace(r.case_name, &r);
  std::set<std::string> out;
  for (const RecordRow& b : base.rows) {
    auto it = new_cases.find(b.case_name);
    if (it == new_cases.end() || it->second->scene_digest == b.scene_digest) continue;
    if (!paired_only)
      throw InputError("refusing to pair '" + b.case_name + "': " + b.source + " and " +
                       it->second->source + " ran different scenes");
    out.insert(b.case_name);
  }
  return out;
}

/// One line of cases left out for a reason, naming the first few.
std::string cases_line(const std::set<std::string>& cases, const std::string& why) {
  std::string line =
      std::to_string(cases.size()) + (cases.size() == 1 ? " case " : " cases ") + why + ": ";
  int named = 0;
  for (const std::string& c : cases) {
    if (named == 4) {
      line += ", ...";
      break;
    }
    line += (named++ ? ", " : "") + c;
  }
  return line;
}

/// paired_only: the sets' cases that both ran on the same scenes; the others summarized.
std::set<std::string> paired_cases(const RecordSet& base, const RecordSet& contender,
                                   const std::set<std::string>& other_scenes,
                                   std::vector<std::string>& unpaired) {
  std::set<std::string> in_base, in_new, both, only_base, only_new;
  for (const RecordRow& r : base.rows) in_base.insert(r.case_name);
  for (const RecordRow& r : contender.rows) in_new.insert(r.case_name);
  for (const std::string& c : in_base) (in_new.count(c) ? both : only_base).insert(c);
  for (const std::string& c : in_new)
    if (!in_base.count(c)) only_new.insert(c);
  for (const std::string& c : other_scenes) both.erase(c);
  if (!only_base.empty()) unpaired.push_back(cases_line(only_base, "only BASE ran"));
  if (!only_new.empty()) unpaired.push_back(cases_line(only_new, "only NEW ran"));
  if (!other_scenes.empty())
    unpaired.push_back(cases_line(other_scenes, "both ran, on other scenes or settings"));
  return both;
}

/// The cases of each gated phase, and their summed medians, for the stratified rows.
struct PhaseStrata {
  std::map<std::string, std::vector<Stratum>> cases;
  std::map<std::string, std::pair<double, double>> totals;

  void add(const RecordRow& b, const RecordRow& n, const RowComparison& c) {
    if (c.unit_of_sample != "runs" || c.test.base_count < 3 || c.test.new_count < 3 ||
        c.note.find("not gated") != std::string::npos)
      return;
    const bool per_run = b.runs.size() >= 3 && n.runs.size() >= 3;
    cases[b.quantity].push_back({test_samples(b, per_run), test_samples(n, per_run)});
    totals[b.quantity].first += c.base_value;
    totals[b.quantity].second += c.new_value;
  }

  /// A phase's code runs in every case: its shift tested across them at once (van Elteren).
  void append_rows(std::vector<RowComparison>& rows, const CompareOptions& options) const {
    for (const auto& [quantity, strata] : cases) {
      if (strata.size() < 2) continue;
      RowComparison c;
      c.case_name = "all cases";
      c.quantity = quantity;
      c.kind = RowKind::Timed;
      c.unit_of_sample = "runs";
      c.test = stratified_shift_test(strata, options.alpha);
      c.p_adjusted = c.test.p_value;
      c.base_value = totals.at(quantity).first;
      c.new_value = totals.at(quantity).second;
      c.note = std::to_string(strata.size()) + " cases stratified (van Elteren); ms summed";
      rows.push_back(std::move(c));
    }
  }
};

RowComparison compare_pair(const RecordRow& b, const RecordRow& n, const CompareOptions& options) {
  switch (b.kind) {
    case RowKind::Timed:
      return timed(b, n, options);
    case RowKind::Counter:
      return counter(b, n);
    case RowKind::Accuracy:
      return accuracy(b, n, options);
    case RowKind::Field:
      return field(b, n, options);
    case RowKind::Count:
      return work_count(b, n, options);
  }
  throw std::logic_error("compare_pair: unhandled kind");
}

/// The phase a count row counts ("update/galerkin" of "update/galerkin D1 misses"), and its event.
std::pair<std::string, std::string> counted_phase(const std::string& quantity) {
  for (const char* event : {" instructions", " D1 misses", " LL misses"})
    if (quantity.ends_with(event))
      return {quantity.substr(0, quantity.size() - std::string(event).size()), event + 1};
  return {quantity, ""};
}

/// Where a timed row also has counts of its phase on both sides, whether the timing moved with
/// the work or without it. A phase's counts include its parts' ("update" holds
/// "update/galerkin"); a step's are every phase's and what runs between them. Counts are taken at
/// one thread: at two they are the same work, spread.
void attribute_timings(std::vector<RowComparison>& rows) {
  struct Moves {
    bool counted = false;
    double largest = 0;  ///< the largest relative move beyond its threshold, signed
    std::string what;
  };
  std::map<std::string, Moves> by_case_phase;  // "case | phase"; "all cases | phase" for any case
  for (const RowComparison& r : rows) {
    if (r.kind != RowKind::Count || r.verdict == "not compared" || r.verdict == "missing in new" ||
        r.verdict == "new row")
      continue;
    const auto [phase, event] = counted_phase(r.quantity);
    const bool top = phase.find('/') == std::string::npos;  // parts are in their phase's counts
    const bool moved = r.verdict == "more" || r.verdict == "fewer";
    const double change = r.test.ratio - 1;
    for (const std::string& key : {r.case_name + " | " + phase, "all cases | " + phase,
                                   r.case_name + " | step", std::string("all cases | step")}) {
      if (!top && key.ends_with("| step")) continue;
      Moves& m = by_case_phase[key];
      m.counted = true;
      if (moved && std::abs(change) > std::abs(m.largest)) {
        m.largest = change;
        m.what =
            r.case_name + " " + r.quantity + " " + (change > 0 ? "+" : "") + fixed_percent(change);
      }
    }
  }
  // A timed case without counts of its own (a report's Table 1 row beside the counted gate suite)
  // takes its phase's counts over every counted case: a change to a phase's code moves that phase
  // in every scene that runs it.
  for (RowComparison& r : rows) {
    if (r.kind != RowKind::Timed) continue;
    auto it = by_case_phase.find(r.case_name + " | " + r.quantity);
    const bool own = it != by_case_phase.end();
    if (!own) it = by_case_phase.find("all cases | " + r.quantity);
    if (it == by_case_phase.end() || !it->second.counted) continue;
    r.attribution = it->second.largest != 0 ? "code" : "machine";
    r.attribution_note = it->second.largest != 0 ? it->second.what
                         : own                   ? "its counts did not move"
                                                 : "its phase's counts did not move in any case";
  }
}

/// A row only one side has: its verdict and the file it came from.
RowComparison unpaired(const RecordRow& r, const std::string& verdict) {
  RowComparison c;
  c.verdict = verdict;
  c.note = r.source;
  return c;
}

}  // namespace

Comparison compare_records(const RecordSet& base, const RecordSet& contender,
                           const CompareOptions& options) {
  Comparison out;
  out.options = options;
  out.warnings = context_warnings(base, contender);
  out.base_context = first_context(base);
  out.new_context = first_context(contender);
  const std::set<std::string> other_scenes = different_scenes(base, contender, options.paired_only);
  std::set<std::string> kept;  // paired_only: the cases compared
  if (options.paired_only) kept = paired_cases(base, contender, other_scenes, out.unpaired);
  const auto left_out = [&](const RecordRow& r) {
    return options.paired_only && !kept.count(r.case_name);
  };
  std::map<std::string, const RecordRow*> new_rows;
  std::set<std::string> new_cases;
  for (const RecordRow& r : contender.rows) {
    if (left_out(r)) continue;
    new_rows[r.key()] = &r;
    new_cases.insert(r.case_name);
  }
  int paired = 0;
  PhaseStrata strata;
  const auto labelled = [](RowComparison c, const RecordRow& r) {
    c.case_name = r.case_name;
    c.quantity = r.quantity;
    c.threads = r.threads;
    c.kind = r.kind;
    return c;
  };
  for (const RecordRow& b : base.rows) {
    if (left_out(b)) continue;
    auto it = new_rows.find(b.key());
    if (it == new_rows.end() || it->second->kind != b.kind) {
      RowComparison c = unpaired(b, "missing in new");
      // A case NEW no longer completes is a failure, not a speed-up; a quantity alone (a phase
      // under the clock's resolution) is only listed.
      c.regression = !new_cases.count(b.case_name);
      out.rows.push_back(labelled(std::move(c), b));
      continue;
    }
    ++paired;
    RowComparison c = compare_pair(b, *it->second, options);
    strata.add(b, *it->second, c);
    new_rows.erase(it);
    out.rows.push_back(labelled(std::move(c), b));
  }
  for (const auto& [key, n] : new_rows) out.rows.push_back(labelled(unpaired(*n, "new row"), *n));
  strata.append_rows(out.rows, options);
  holm_verdicts(out.rows, options);
  attribute_timings(out.rows);
  if (const std::string w = provenance_warning(base, contender); !w.empty())
    out.warnings.push_back(w);
  if (paired == 0)
    throw InputError(
        "no row of BASE pairs with a row of NEW (different cases, thread counts or "
        "kinds of record)" +
        std::string(out.unpaired.empty() ? "" : ": " + out.unpaired.front()));
  return out;
}

}  // namespace corofem
