#include "scene/time_step_scaling.hpp"

namespace corofem {
using nlohmann::json;

std::optional<json> time_step_scaled(const json& scene, int numerator, int denominator) {
  json s = scene;
  bool whole = true;
  auto scale = [&](json& count) {
    const long long scaled = count.get<long long>() * denominator;
    whole &= scaled % numerator == 0;
    count = scaled / numerator;
  };
  json& analysis = s["analysis"];
  analysis["dt"] = analysis.value("dt", 0.01) * numerator / denominator;
  if (!analysis.contains("steps")) analysis["steps"] = 1;
  scale(analysis["steps"]);
  for (const char* loads : {"forces", "moves"})
    if (s.contains(loads))
      for (json& load : s[loads])
        for (const char* key : {"ramp_steps", "release_step"})
          if (load.contains(key)) scale(load[key]);
  if (!whole || analysis["steps"].get<long long>() < 1) return std::nullopt;
  return s;
}

}  // namespace corofem
