#include "scene/json_fields.hpp"

#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace corofem {
namespace {
[[noreturn]] void error(const std::string& file, const std::string& path, const std::string& what) {
  throw InputError("scene '" + file + "': " + path + " " + what);
}
/// Nonzero and below the smallest normal double: arithmetic on it is slow and loses digits.
bool is_denormal(double x) {
  return x != 0 && std::abs(x) < std::numeric_limits<double>::min();
}
}  // namespace

JsonFields::JsonFields(const nlohmann::json& object, std::string path, std::string file)
    : object_(object), path_(std::move(path)), file_(std::move(file)) {
  if (!object_.is_object())
    error(file_, path_.empty() ? "(top level)" : path_, "must be an object");
}

std::string JsonFields::path_of(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool JsonFields::has(const std::string& key) const {
  return object_.contains(key);
}

const nlohmann::json* JsonFields::get(const std::string& key) {
  known_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

const nlohmann::json& JsonFields::require(const std::string& key) {
  const nlohmann::json* v = get(key);
  if (!v) error(file_, path_of(key), "is required");
  return *v;
}

JsonFields JsonFields::object(const std::string& key) {
  return JsonFields(require(key), path_of(key), file_);
}

/// The value at key; nullptr when it is missing and a fallback exists, an error when not.
template <class T>
const nlohmann::json* JsonFields::value_or_fallback(const std::string& key,
                                                    const std::optional<T>& fallback) {
  const nlohmann::json* v = get(key);
  if (!v && !fallback) error(file_, path_of(key), "is required");
  return v;
}

double JsonFields::number(const std::string& key, std::optional<double> fallback) {
  const nlohmann::json* v = value_or_fallback(key, fallback);
  if (!v) return *fallback;
  if (!v->is_number()) error(file_, path_of(key), "must be a number");
  const double d = v->get<double>();
  if (!std::isfinite(d)) error(file_, path_of(key), "must be finite");
  if (is_denormal(d))
    error(file_, path_of(key), "must not be a denormal number (0 < |x| < 2.2e-308)");
  return d;
}

int JsonFields::integer(const std::string& key, std::optional<int> fallback) {
  const nlohmann::json* v = value_or_fallback(key, fallback);
  if (!v) return *fallback;
  if (!v->is_number_integer()) error(file_, path_of(key), "must be an integer");
  const auto i = v->get<long long>();
  if (i < -2147483647LL || i > 2147483647LL) error(file_, path_of(key), "is out of range");
  return static_cast<int>(i);
}

bool JsonFields::boolean(const std::string& key, std::optional<bool> fallback) {
  const nlohmann::json* v = value_or_fallback(key, fallback);
  if (!v) return *fallback;
  if (!v->is_boolean()) error(file_, path_of(key), "must be true or false");
  return v->get<bool>();
}

std::string JsonFields::string(const std::string& key, std::optional<std::string> fallback) {
  const nlohmann::json* v = value_or_fallback(key, fallback);
  if (!v) return *fallback;
  if (!v->is_string()) error(file_, path_of(key), "must be a string");
  return v->get<std::string>();
}

Vec3 JsonFields::vec3(const std::string& key, std::optional<Vec3> fallback) {
  const nlohmann::json* v = value_or_fallback(key, fallback);
  if (!v) return *fallback;
  return json_vec3(*v, path_of(key), file_);
}

void JsonFields::fail(const std::string& key, const std::string& what) const {
  error(file_, path_of(key), "must be " + what);
}

void JsonFields::reject_unknown_keys() const {
  for (const auto& [key, value] : object_.items())
    if (!known_.count(key)) error(file_, path_of(key), "is not a known key");
}

Vec3 json_vec3(const nlohmann::json& value, const std::string& path, const std::string& file) {
  if (!value.is_array() || value.size() != 3) error(file, path, "must be an array of 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!value[i].is_number()) error(file, path, "must be an array of 3 numbers");
    v[i] = value[i].get<double>();
    if (!std::isfinite(v[i])) error(file, path, "must contain finite numbers");
    if (is_denormal(v[i]))
      error(file, path, "must not contain a denormal number (0 < |x| < 2.2e-308)");
  }
  return v;
}

}  // namespace corofem
