#include "scene/component_settings.hpp"

#include <cmath>
#include <sstream>

namespace corofem {

namespace {

std::string bound_text(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

void check_range(JsonFields& f, const ParameterSpec& spec, double value) {
  if (!(value >= spec.min && value <= spec.max))
    f.fail(spec.key, "in [" + bound_text(spec.min) + ", " + bound_text(spec.max) + "]");
}

ParameterValue read_one(JsonFields& f, const ParameterSpec& spec) {
  switch (spec.kind) {
    case ParameterSpec::Kind::Flag:
      return f.boolean(spec.key);
    case ParameterSpec::Kind::Integer: {
      const int value = f.integer(spec.key);
      check_range(f, spec, value);
      return static_cast<long long>(value);
    }
    case ParameterSpec::Kind::Number: {
      const double value = f.number(spec.key);
      check_range(f, spec, value);
      return value;
    }
    case ParameterSpec::Kind::Text: {
      std::string value = f.string(spec.key);
      if (spec.choices.empty()) return value;
      for (const std::string& choice : spec.choices)
        if (choice == value) return value;
      std::string list;
      for (const std::string& choice : spec.choices) list += (list.empty() ? "" : ", ") + choice;
      f.fail(spec.key, "one of: " + list + " (got '" + value + "')");
    }
  }
  return spec.fallback;
}

}  // namespace

Parameters read_parameters(JsonFields& f, const std::vector<ParameterSpec>& specs) {
  Parameters values(specs);
  for (const ParameterSpec& spec : specs)
    if (f.has(spec.key)) values.set(spec.key, read_one(f, spec));
  return values;
}

}  // namespace corofem
