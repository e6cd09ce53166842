#include "core/parameters.hpp"

#include <stdexcept>

namespace corofem {

Parameters::Parameters(const std::vector<ParameterSpec>& specs) {
  for (const ParameterSpec& spec : specs) values_[spec.key] = spec.fallback;
}

void Parameters::set(std::string key, ParameterValue value) {
  values_[std::move(key)] = std::move(value);
}

bool Parameters::has(std::string_view key) const {
  return values_.find(key) != values_.end();
}

const ParameterValue& Parameters::at(std::string_view key) const {
  const auto it = values_.find(key);
  if (it == values_.end())
    throw std::out_of_range("no setting '" + std::string(key) + "' (the component declares none)");
  return it->second;
}

namespace {

template <class T>
const T& as(const ParameterValue& value, std::string_view key, const char* kind) {
  if (const T* v = std::get_if<T>(&value)) return *v;
  throw std::out_of_range("setting '" + std::string(key) + "' is not " + kind);
}

}  // namespace

bool Parameters::flag(std::string_view key) const {
  return as<bool>(at(key), key, "a flag");
}

long long Parameters::integer(std::string_view key) const {
  return as<long long>(at(key), key, "an integer");
}

double Parameters::number(std::string_view key) const {
  const ParameterValue& value = at(key);
  if (const long long* i = std::get_if<long long>(&value)) return static_cast<double>(*i);
  return as<double>(value, key, "a number");
}

const std::string& Parameters::text(std::string_view key) const {
  return as<std::string>(at(key), key, "a text");
}

}  // namespace corofem
