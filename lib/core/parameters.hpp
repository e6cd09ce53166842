#pragma once
// Settings that a component declares and owns (in the manner of Ginkgo's factory parameters): each
// has its scene key, its kind, its default, what it admits and what it means. The scene reader
// fills a component's values from the scene by its declarations alone (scene/component_settings);
// the component reads them by key, and describes itself to the records with values of the same
// kinds. No JSON here: the records' writers turn values into JSON (io/).
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace corofem {

/// The least relative tolerance a setting may ask for: below it no double residual gets.
inline constexpr double kMinTolerance = 1e-15;

/// A setting's value: a flag, an integer, a number, a text, or a list of numbers (a record's
/// interval).
using ParameterValue = std::variant<bool, long long, double, std::string, std::vector<double>>;

struct ParameterSpec {
  enum class Kind { Flag, Integer, Number, Text };
  std::string key;  ///< the scene's analysis.<key>
  Kind kind = Kind::Number;
  ParameterValue fallback{0.0};                           ///< the default, of the kind
  double min = -std::numeric_limits<double>::infinity();  ///< Integer, Number: admitted range
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices{};  ///< Text: the admitted values (empty: any)
  std::string meaning{};               ///< one line for the scene format's reference
};

/// A component's values by key: a scene's, its defaults where the scene gives none, or what the
/// component says of itself.
class Parameters {
 public:
  Parameters() = default;
  /// Every declared key at its default.
  explicit Parameters(const std::vector<ParameterSpec>& specs);

  void set(std::string key, ParameterValue value);
  bool has(std::string_view key) const;
  /// The value of `key`, of the kind asked; std::out_of_range naming the key when it is absent or
  /// of another kind (a component that reads a key it did not declare).
  bool flag(std::string_view key) const;
  long long integer(std::string_view key) const;
  double number(std::string_view key) const;  ///< an integer reads as a number too
  const std::string& text(std::string_view key) const;
  /// Every value, by key.
  const std::map<std::string, ParameterValue, std::less<>>& values() const { return values_; }
  bool operator==(const Parameters& other) const = default;

 private:
  const ParameterValue& at(std::string_view key) const;
  std::map<std::string, ParameterValue, std::less<>> values_;
};

}  // namespace corofem
