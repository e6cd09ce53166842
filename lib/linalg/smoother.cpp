// The registry behind smoother.hpp: the built-ins, each from its own file, then whatever a
// user's program registers.
#include "linalg/smoother.hpp"

#include <deque>
#include <stdexcept>

#include "linalg/chebyshev_smoother.hpp"
#include "linalg/gauss_seidel_smoother.hpp"

namespace corofem {
namespace {

/// Registration happens before any run, reading from any thread after.
std::deque<SmootherTraits>& registry() {
  static std::deque<SmootherTraits> smoothers = [] {
    std::deque<SmootherTraits> built_in;
    for (SmootherTraits& t : gauss_seidel_smoothers()) built_in.push_back(std::move(t));
    built_in.push_back(chebyshev_smoother_traits());
    return built_in;
  }();
  return smoothers;
}

}  // namespace

void register_smoother(SmootherTraits traits) {
  if (traits.name.empty()) throw std::invalid_argument("register_smoother: no name");
  if (!traits.make)
    throw std::invalid_argument("register_smoother: '" + traits.name + "' has no make");
  if (find_smoother(traits.name))
    throw std::invalid_argument("register_smoother: '" + traits.name + "' is registered already");
  registry().push_back(std::move(traits));
}

std::vector<std::string> smoother_names() {
  std::vector<std::string> out;
  for (const SmootherTraits& t : registry()) out.push_back(t.name);
  return out;
}

const SmootherTraits* find_smoother(std::string_view name) {
  for (const SmootherTraits& t : registry())
    if (t.name == name) return &t;
  return nullptr;
}

std::unique_ptr<Smoother> make_smoother(std::string_view name, const SmootherSettings& settings) {
  const SmootherTraits* traits = find_smoother(name);
  if (!traits) {
    std::string list;
    for (const std::string& n : smoother_names()) list += (list.empty() ? "" : ", ") + n;
    throw std::out_of_range("no smoother named '" + std::string(name) + "' (registered: " + list +
                            ")");
  }
  std::unique_ptr<Smoother> smoother = traits->make(settings);
  if (!smoother) throw std::logic_error("smoother '" + traits->name + "': its make built nothing");
  return smoother;
}

}  // namespace corofem
