#pragma once
// What `corofem compare` writes: a Markdown table a pull request can show, the JSON verdict, and
// an SVG chart of every timed row's ratio with its interval.
#include <nlohmann/json.hpp>
#include <string>

#include "compare/comparison.hpp"

namespace corofem {

/// Markdown: the verdict, the warnings, every timed row, the counters that changed, the accuracy
/// fields; `base` and `contender` name the two sides.
std::string comparison_markdown(const Comparison& c, const std::string& base,
                                const std::string& contender);

/// The JSON verdict: options, both contexts, the summary and every row.
nlohmann::json comparison_json(const Comparison& c, const std::string& base,
                               const std::string& contender);

/// An SVG chart: NEW/BASE of each gated timed row (log scale) with its interval, grouped by case,
/// the threshold band shaded.
std::string comparison_svg(const Comparison& c);

}  // namespace corofem
