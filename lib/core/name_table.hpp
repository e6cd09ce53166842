#pragma once
// The names of a setting's values, one table per setting, used both to parse a scene's string
// (scene/ only) and to write the value into records, so that the two cannot disagree.
#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace corofem {

template <class Enum, std::size_t N>
struct NameTable {
  std::array<std::pair<Enum, const char*>, N> entries;

  const char* name(Enum value) const {
    for (const auto& [v, n] : entries)
      if (v == value) return n;
    return "?";
  }
  std::optional<Enum> find(std::string_view name) const {
    for (const auto& [v, n] : entries)
      if (name == n) return v;
    return std::nullopt;
  }
  /// The value named `name`; std::out_of_range for another (tests and benchmarks: a scene's
  /// strings go through scene/'s parser, which names the key).
  Enum at(std::string_view name) const {
    if (auto value = find(name)) return *value;
    throw std::out_of_range("no value named '" + std::string(name) + "'");
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : entries) out.emplace_back(entry.second);
    return out;
  }
};

}  // namespace corofem
