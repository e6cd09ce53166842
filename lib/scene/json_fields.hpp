#pragma once
// Reading one JSON object of a scene with errors that name the file and the key path
// ("scene 'a.json': analysis.dt must be > 0, got -1"), and a check for unknown keys.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "mesh/tet_mesh.hpp"

namespace corofem {

class JsonFields {
 public:
  /// `object` must be a JSON object, else InputError naming `path`.
  JsonFields(const nlohmann::json& object, std::string path, std::string file);

  bool has(const std::string& key) const;
  /// The value at key, or nullptr; marks the key as known.
  const nlohmann::json* get(const std::string& key);
  const nlohmann::json& require(const std::string& key);
  /// Sub-object reader for key (must be an object).
  JsonFields object(const std::string& key);

  double number(const std::string& key, std::optional<double> fallback = std::nullopt);
  int integer(const std::string& key, std::optional<int> fallback = std::nullopt);
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
  std::string string(const std::string& key, std::optional<std::string> fallback = std::nullopt);
  Vec3 vec3(const std::string& key, std::optional<Vec3> fallback = std::nullopt);

  /// Throws if the value at key (already read) fails `ok`, with "must be <what>".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  /// InputError for any key that was never asked for.
  void reject_unknown_keys() const;

  std::string path_of(const std::string& key) const;
  const std::string& file() const { return file_; }

 private:
  template <class T>
  const nlohmann::json* value_or_fallback(const std::string& key, const std::optional<T>& fallback);

  const nlohmann::json& object_;
  std::string path_, file_;
  std::set<std::string> known_;
};

/// [x, y, z] of finite numbers, else InputError naming `path`.
Vec3 json_vec3(const nlohmann::json& value, const std::string& path, const std::string& file);

}  // namespace corofem
