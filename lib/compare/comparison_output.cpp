#include "compare/comparison_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/number_text.hpp"

namespace corofem {
namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

/// A count as digits in groups of three: 743,384,102.
std::string count_text(double v) {
  if (!std::isfinite(v) || v < 0 || v > 9e18) return general_number(v);
  std::string digits = std::to_string(static_cast<unsigned long long>(std::llround(v)));
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(i, ",");
  return digits;
}

/// A stratified row spans every thread count: "all".
std::string threads_text(int threads) {
  return threads > 0 ? std::to_string(threads) : "all";
}

/// Text for an SVG element: the markup characters escaped.
std::string xml_text(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else
      out += ch;
  }
  return out;
}

/// Counts of each verdict among the rows.
std::map<std::string, int> verdict_counts(const Comparison& c) {
  std::map<std::string, int> counts;
  for (const RowComparison& r : c.rows) ++counts[r.verdict];
  return counts;
}

std::string summary_line(const Comparison& c) {
  std::string line = "**" + c.headline() + "**";
  line += " (";
  bool first = true;
  for (const auto& [verdict, count] : verdict_counts(c)) {
    line += (first ? "" : ", ") + std::to_string(count) + " " + verdict;
    first = false;
  }
  return line + ")";
}

/// What the comparison could not test, its largest ratios, and the runs that would test it.
std::string untested_text(const Comparison& c) {
  if (c.untested() == 0) return {};
  std::vector<const RowComparison*> rows;
  for (const RowComparison& r : c.rows)
    if (r.kind == RowKind::Timed && (r.verdict == "inconclusive" || r.verdict == "suspect"))
      rows.push_back(&r);
  std::sort(rows.begin(), rows.end(), [](const RowComparison* a, const RowComparison* b) {
    return std::abs(std::log(a->test.ratio)) > std::abs(std::log(b->test.ratio));
  });
  std::ostringstream md;
  md << c.untested() << " timed row" << (c.untested() == 1 ? "" : "s")
     << " could not be tested (too few runs a side); the largest ratios NEW/BASE:";
  for (std::size_t i = 0; i < rows.size() && i < 3; ++i)
    md << (i ? "," : "") << " " << fixed(rows[i]->test.ratio, 3) << " (" << rows[i]->case_name
       << ", " << rows[i]->quantity << (rows[i]->verdict == "suspect" ? ", **suspect**" : "")
       << ")";
  md << ". " << c.runs_to_decide()
     << " runs a side would test them: --benchmark_repetitions=" << c.runs_to_decide()
     << " for Google Benchmark, --runs " << c.runs_to_decide() << " for ci/bench-gate.\n\n";
  return md.str();
}

std::string context_text(const nlohmann::json& context) {
  if (!context.is_object()) return "no context recorded";
  auto field = [&](const char* key) {
    return context.contains(key) && context[key].is_string() ? context[key].get<std::string>()
                                                             : std::string("?");
  };
  return "commit `" + field("commit").substr(0, 9) + "`, " + field("cpu") + ", " +
         field("compiler") + " `" + field("flags") + "`, " + field("date");
}

const char* kind_name(RowKind kind) {
  switch (kind) {
    case RowKind::Timed:
      return "timed";
    case RowKind::Counter:
      return "counter";
    case RowKind::Accuracy:
      return "accuracy";
    case RowKind::Field:
      return "field";
    case RowKind::Count:
      return "count";
  }
  return "?";
}

/// The work counts' table: the rows that moved beyond their threshold (or could not be
/// compared), and how many did not.
std::string work_counts_markdown(const Comparison& c) {
  std::map<std::string, int> quiet;
  std::ostringstream moved;
  for (const RowComparison& r : c.rows) {
    if (r.kind != RowKind::Count) continue;
    if (r.verdict == "equal" || r.verdict == "within threshold") {
      ++quiet[r.verdict];
      continue;
    }
    const bool flag =
        r.regression || (r.verdict == "fewer" && r.note.find("not gated") == std::string::npos);
    moved << "| " << r.case_name << " | " << r.quantity << " | " << count_text(r.base_value)
          << " | " << count_text(r.new_value) << " | "
          << (r.base_value > 0 && std::isfinite(r.test.ratio)
                  ? (r.test.ratio >= 1 ? "+" : "") + fixed(100 * (r.test.ratio - 1), 2) + "%"
                  : std::string("-"))
          << " | " << (flag ? "**" + r.verdict + "**" : r.verdict)
          << (r.note.empty() ? "" : " (" + r.note + ")") << " |\n";
  }
  if (quiet.empty() && moved.str().empty()) return {};
  const CompareOptions& o = c.options;
  std::ostringstream md;
  md << "\nWork counts (more or fewer: instructions moved by more than "
     << general_number(100 * o.count_threshold) << "%, D1 or LL misses by more than "
     << general_number(100 * o.miss_threshold)
     << "%, a phase's (a solver part's shown, not gated); BASE under "
     << general_number(o.min_count) << " shown, not gated): " << quiet["equal"] << " equal, "
     << quiet["within threshold"] << " within threshold";
  if (moved.str().empty()) return md.str() + ".\n";
  md << ", and these:\n\n| case | quantity | BASE | NEW | change | verdict |\n"
     << "|---|---|---|---|---|---|\n"
     << moved.str();
  return md.str();
}

}  // namespace

std::string comparison_markdown(const Comparison& c, const std::string& base,
                                const std::string& contender) {
  std::ostringstream md;
  const CompareOptions& o = c.options;
  md << "## corofem compare\n\n"
     << "BASE `" << base << "`: " << context_text(c.base_context) << "  \n"
     << "NEW `" << contender << "`: " << context_text(c.new_context) << "\n\n"
     << summary_line(c) << ". A timing is slower or faster when the U test's p, adjusted over "
     << "the gated rows (Holm), is under " << general_number(o.alpha)
     << " and the Hodges-Lehmann ratio is beyond " << general_number(o.threshold * 100)
     << "%; intervals at " << general_number(100 - 100 * o.alpha) << "%.\n\n";
  md << untested_text(c);
  for (const std::string& u : c.unpaired) md << "- not compared: " << u << "\n";
  if (!c.unpaired.empty()) md << "\n";
  for (const std::string& w : c.warnings) md << "- warning: " << w << "\n";
  if (!c.warnings.empty()) md << "\n";

  const bool timed_rows = std::any_of(c.rows.begin(), c.rows.end(), [](const RowComparison& r) {
    return r.kind == RowKind::Timed && r.verdict != "missing in new" && r.verdict != "new row";
  });
  if (timed_rows)
    md << "| case | threads | quantity | BASE ms | NEW ms | NEW/BASE | interval | p | p (Holm) | "
          "samples | verdict |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const RowComparison& r : c.rows) {
    if (r.kind != RowKind::Timed || r.verdict == "missing in new" || r.verdict == "new row")
      continue;
    const bool flag = r.verdict == "slower" || r.verdict == "faster";
    md << "| " << r.case_name << " | " << threads_text(r.threads) << " | " << r.quantity << " | "
       << general_number(r.base_value) << " | " << general_number(r.new_value) << " | "
       << fixed(r.test.ratio, 3) << " | " << fixed(r.test.ratio_low, 3) << "-"
       << fixed(r.test.ratio_high, 3) << " | " << general_number(r.test.p_value) << " | "
       << general_number(r.p_adjusted) << " | " << r.test.base_count << "/" << r.test.new_count
       << " " << r.unit_of_sample << " | " << (flag ? "**" + r.verdict + "**" : r.verdict)
       << (r.note.empty() ? "" : " (" + r.note + ")")
       << (r.attribution.empty() ? "" : "; the " + r.attribution + "'s: " + r.attribution_note)
       << " |\n";
  }
  md << work_counts_markdown(c);
  int equal_counters = 0;
  std::ostringstream changed;
  for (const RowComparison& r : c.rows) {
    if (r.kind == RowKind::Count) continue;
    if (r.kind == RowKind::Counter && r.verdict == "equal") {
      ++equal_counters;
    } else if (r.kind != RowKind::Timed || r.verdict == "missing in new" ||
               r.verdict == "new row") {
      changed << "| " << r.case_name << " | " << threads_text(r.threads) << " | " << r.quantity
              << " | " << kind_name(r.kind) << " | "
              << (r.kind == RowKind::Field ? std::string() : general_number(r.base_value)) << " | "
              << general_number(r.new_value) << " | "
              << (r.regression ? "**" + r.verdict + "**" : r.verdict)
              << (r.note.empty() ? "" : " (" + r.note + ")") << " |\n";
    }
  }
  md << "\nCounters (exact), accuracy fields (worse: grown more than "
     << general_number(o.accuracy_factor) << "x and past " << general_number(o.accuracy_floor)
     << "), final displacements (|du|/|u| within " << general_number(o.field_tolerance) << "); "
     << equal_counters << " counters equal and not listed:\n\n"
     << "| case | threads | quantity | kind | BASE | NEW | verdict |\n"
        "|---|---|---|---|---|---|---|\n"
     << changed.str();
  return md.str();
}

nlohmann::json comparison_json(const Comparison& c, const std::string& base,
                               const std::string& contender) {
  const CompareOptions& o = c.options;
  nlohmann::json rows = nlohmann::json::array();
  for (const RowComparison& r : c.rows) {
    nlohmann::json row = {{"case", r.case_name},    {"threads", r.threads},
                          {"quantity", r.quantity}, {"kind", kind_name(r.kind)},
                          {"verdict", r.verdict},   {"regression", r.regression},
                          {"base", r.base_value},   {"new", r.new_value}};
    if (r.kind == RowKind::Timed && !r.unit_of_sample.empty())
      row["test"] = {{"ratio", r.test.ratio},
                     {"interval", {r.test.ratio_low, r.test.ratio_high}},
                     {"p_value", r.test.p_value},
                     {"p_adjusted", r.p_adjusted},
                     {"u", r.test.u},
                     {"exact", r.test.exact},
                     {"samples", {r.test.base_count, r.test.new_count}},
                     {"unit_of_sample", r.unit_of_sample}};
    if (!std::isfinite(r.new_value)) row["new"] = nullptr;
    if (r.kind == RowKind::Count && std::isfinite(r.test.ratio)) row["ratio"] = r.test.ratio;
    if (!r.note.empty()) row["note"] = r.note;
    if (!r.attribution.empty())
      row["attribution"] = {{"to", r.attribution}, {"because", r.attribution_note}};
    rows.push_back(std::move(row));
  }
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [verdict, count] : verdict_counts(c)) counts[verdict] = count;
  return {{"producer", "corofem compare"},
          {"base", base},
          {"new", contender},
          {"base_context", c.base_context},
          {"new_context", c.new_context},
          {"options",
           {{"threshold", o.threshold},
            {"alpha", o.alpha},
            {"accuracy_factor", o.accuracy_factor},
            {"accuracy_floor", o.accuracy_floor},
            {"field_tolerance", o.field_tolerance},
            {"min_ms", o.min_ms},
            {"suspect_factor", o.suspect_factor},
            {"paired_only", o.paired_only},
            {"count_threshold", o.count_threshold},
            {"miss_threshold", o.miss_threshold},
            {"min_count", o.min_count},
            {"test",
             "Mann-Whitney U (two-sided) on log times, p adjusted over the gated rows (Holm); "
             "Hodges-Lehmann ratio and its distribution-free interval"}}},
          {"regression", c.regressed()},
          {"headline", c.headline()},
          {"untested", c.untested()},
          {"runs_to_decide", c.runs_to_decide()},
          {"counts_fell", c.counts_fell()},
          {"verdicts", counts},
          {"warnings", c.warnings},
          {"unpaired", c.unpaired},
          {"rows", rows}};
}

std::string comparison_svg(const Comparison& c) {
  std::vector<const RowComparison*> rows;
  for (const RowComparison& r : c.rows)
    if (r.kind == RowKind::Timed && !r.unit_of_sample.empty()) rows.push_back(&r);
  const double row_h = 16, left = 420, plot_w = 360, top = 40;
  const double height = top + row_h * static_cast<double>(rows.size()) + 40;
  // Log axis over the intervals and the threshold, at least 0.8-1.25.
  double lo = std::log(0.8), hi = std::log(1.25);
  for (const RowComparison* r : rows) {
    lo = std::min(lo, std::log(std::max(r->test.ratio_low, 1e-3)));
    hi = std::max(hi, std::log(std::min(r->test.ratio_high, 1e3)));
  }
  auto x = [&](double ratio) {
    const double v = std::clamp(std::log(ratio), lo, hi);
    return left + (v - lo) / (hi - lo) * plot_w;
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << left + plot_w + 120 << "\" height=\""
    << height << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"8\" y=\"18\" font-size=\"13\">NEW/BASE per timed row, Hodges-Lehmann ratio with "
    << fixed(100 - 100 * c.options.alpha, 0) << "% interval (log scale); band: +-"
    << general_number(100 * c.options.threshold) << "%</text>\n";
  const double band_lo = x(1 / (1 + c.options.threshold)), band_hi = x(1 + c.options.threshold);
  s << "<rect x=\"" << band_lo << "\" y=\"" << top - 6 << "\" width=\"" << band_hi - band_lo
    << "\" height=\"" << row_h * static_cast<double>(rows.size()) + 6
    << "\" fill=\"#e8e8e8\"/>\n<line x1=\"" << x(1) << "\" x2=\"" << x(1) << "\" y1=\"" << top - 6
    << "\" y2=\"" << top + row_h * static_cast<double>(rows.size()) << "\" stroke=\"#444\"/>\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const RowComparison& r = *rows[i];
    const double y = top + row_h * static_cast<double>(i) + row_h / 2;
    const char* colour = r.verdict == "slower"   ? "#c0392b"
                         : r.verdict == "faster" ? "#27ae60"
                                                 : "#2c3e50";
    s << "<text x=\"8\" y=\"" << y + 4 << "\">" << xml_text(r.case_name) << " | "
      << threads_text(r.threads) << "t | " << xml_text(r.quantity) << "</text>\n"
      << "<line x1=\"" << x(r.test.ratio_low) << "\" x2=\"" << x(r.test.ratio_high) << "\" y1=\""
      << y << "\" y2=\"" << y << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n"
      << "<circle cx=\"" << x(r.test.ratio) << "\" cy=\"" << y << "\" r=\"3.5\" fill=\"" << colour
      << "\"/>\n<text x=\"" << left + plot_w + 8 << "\" y=\"" << y + 4 << "\">"
      << fixed(r.test.ratio, 3) << " " << r.verdict << "</text>\n";
  }
  const double axis_y = top + row_h * static_cast<double>(rows.size()) + 16;
  for (double tick : {0.5, 0.8, 0.9, 1.0, 1.1, 1.25, 2.0})
    if (std::log(tick) >= lo && std::log(tick) <= hi)
      s << "<text x=\"" << x(tick) - 10 << "\" y=\"" << axis_y << "\">" << general_number(tick)
        << "</text>\n";
  s << "</svg>\n";
  return s.str();
}

}  // namespace corofem
