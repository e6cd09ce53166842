// The registry behind rotation_method.hpp: the built-ins' traits, each from its own file, then
// whatever a user's program registers.
#include <deque>
#include <stdexcept>

#include "core/named_registry.hpp"
#include "rotation/energy_rotation.hpp"
#include "rotation/gram_schmidt_frame.hpp"
#include "rotation/mueller2016.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/rotation_extractor.hpp"
#include "rotation/smoothed_polar.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {
namespace {

std::deque<RotationMethodTraits> builtin_methods() {
  std::deque<RotationMethodTraits> methods{
      energy_newton_traits(),  energy_exact_traits(), polar_traits(),       polar_fixed_traits(),
      polar_smoothed_traits(), qr_traits(),           mueller2016_traits(), identity_traits(),
  };
  // In the order of the RotationMethod constants.
  const std::pair<RotationMethod, const char*> fixed[] = {
      {RotationMethod::EnergyNewton, "energy-newton"},
      {RotationMethod::EnergyExact, "energy-exact"},
      {RotationMethod::Polar, "polar"},
      {RotationMethod::PolarFixed, "polar-fixed"},
      {RotationMethod::PolarSmoothed, "polar-smoothed"},
      {RotationMethod::Qr, "qr"},
      {RotationMethod::Mueller2016, "mueller2016"},
      {RotationMethod::None, "none"}};
  for (const auto& [method, name] : fixed)
    if (methods.at(static_cast<std::size_t>(method.id())).name != name)
      throw std::logic_error("rotation registry: built-in " + std::to_string(method.id()) +
                             " is not '" + name + "'");
  return methods;
}

NamedRegistry<RotationMethodTraits>& registry() {
  static NamedRegistry<RotationMethodTraits> methods(builtin_methods(), "rotation method");
  return methods;
}

}  // namespace

const RotationMethodTraits& RotationMethod::traits() const {
  return registry().at(static_cast<std::size_t>(id_));
}

const std::string& RotationMethod::name() const {
  return traits().name;
}

RotationMethod register_rotation_method(RotationMethodTraits traits) {
  if (!traits.make)
    throw std::invalid_argument("register rotation method: '" + traits.name + "' has no make");
  return RotationMethod(static_cast<int>(registry().add(std::move(traits))));
}

std::vector<RotationMethod> rotation_methods() {
  std::vector<RotationMethod> out;
  for (std::size_t i = 0; i < registry().size(); ++i) out.emplace_back(static_cast<int>(i));
  return out;
}

std::vector<std::string> rotation_method_names() {
  return registry().names();
}

std::optional<RotationMethod> find_rotation_method(std::string_view name) {
  if (auto i = registry().find(name)) return RotationMethod(static_cast<int>(*i));
  return std::nullopt;
}

RotationMethod rotation_method_named(std::string_view name) {
  return RotationMethod(static_cast<int>(registry().index_of(name)));
}

}  // namespace corofem
