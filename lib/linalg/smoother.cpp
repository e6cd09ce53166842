// The registry behind smoother.hpp: the built-ins, each from its own file, then whatever a
// user's program registers.
#include "linalg/smoother.hpp"

#include <deque>
#include <stdexcept>

#include "core/named_registry.hpp"
#include "linalg/chebyshev_smoother.hpp"
#include "linalg/gauss_seidel_smoother.hpp"

namespace corofem {
namespace {

NamedRegistry<SmootherTraits>& registry() {
  static NamedRegistry<SmootherTraits> smoothers(
      [] {
        std::deque<SmootherTraits> built_in;
        for (SmootherTraits& t : gauss_seidel_smoothers()) built_in.push_back(std::move(t));
        built_in.push_back(chebyshev_smoother_traits());
        return built_in;
      }(),
      "smoother");
  return smoothers;
}

}  // namespace

void register_smoother(SmootherTraits traits) {
  if (!traits.make)
    throw std::invalid_argument("register smoother: '" + traits.name + "' has no make");
  registry().add(std::move(traits));
}

std::vector<std::string> smoother_names() {
  return registry().names();
}

const SmootherTraits* find_smoother(std::string_view name) {
  if (auto i = registry().find(name)) return &registry().at(*i);
  return nullptr;
}

std::unique_ptr<Smoother> make_smoother(std::string_view name, const Parameters& values) {
  const SmootherTraits& traits = registry().at(registry().index_of(name));
  Parameters own(traits.parameters);  // its defaults, then what `values` gives of its own
  for (const ParameterSpec& spec : traits.parameters)
    if (values.has(spec.key)) own.set(spec.key, values.values().find(spec.key)->second);
  std::unique_ptr<Smoother> smoother = traits.make(own);
  if (!smoother) throw std::logic_error("smoother '" + traits.name + "': its make built nothing");
  return smoother;
}

std::vector<ParameterSpec> smoother_parameters() {
  std::vector<ParameterSpec> out;
  for (const std::string& name : registry().names())
    for (const ParameterSpec& spec : registry().at(registry().index_of(name)).parameters)
      out.push_back(spec);
  return out;
}

}  // namespace corofem
