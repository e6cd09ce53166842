// The registry behind solver_kind.hpp: the built-ins' traits (scene/solver_factory.cpp, beside
// their makers), then whatever a user's program registers.
#include <deque>
#include <stdexcept>

#include "core/named_registry.hpp"
#include "scene/solver_factory.hpp"
#include "scene/solver_kind.hpp"

namespace corofem {
namespace {

std::deque<SolverTraits> builtin() {
  std::deque<SolverTraits> solvers;
  for (SolverTraits& t : builtin_solvers()) solvers.push_back(std::move(t));
  // In the order of the SolverKind constants.
  const std::pair<SolverKind, const char*> fixed[] = {
      {SolverKind::Cholmod, "cholmod"},      {SolverKind::Multigrid, "multigrid"},
      {SolverKind::Mgpcg, "mgpcg"},          {SolverKind::JacobiPcg, "jacobi-pcg"},
      {SolverKind::PetscGamg, "petsc-gamg"}, {SolverKind::HypreBoomeramg, "hypre-boomeramg"},
      {SolverKind::PetscMg, "petsc-mg"},     {SolverKind::Auto, "auto"}};
  for (const auto& [kind, name] : fixed)
    if (solvers.at(static_cast<std::size_t>(kind.id())).name != name)
      throw std::logic_error("solver registry: built-in " + std::to_string(kind.id()) +
                             " is not '" + name + "'");
  return solvers;
}

NamedRegistry<SolverTraits>& registry() {
  static NamedRegistry<SolverTraits> solvers(builtin(), "solver");
  return solvers;
}

}  // namespace

const SolverTraits& SolverKind::traits() const {
  return registry().at(static_cast<std::size_t>(id_));
}

const std::string& SolverKind::name() const {
  return traits().name;
}

SolverKind register_solver(SolverTraits traits) {
  if (!traits.make)
    throw std::invalid_argument("register solver: '" + traits.name + "' has no make");
  return SolverKind(static_cast<int>(registry().add(std::move(traits))));
}

std::vector<SolverKind> solver_kinds() {
  std::vector<SolverKind> out;
  for (std::size_t i = 0; i < registry().size(); ++i) out.emplace_back(static_cast<int>(i));
  return out;
}

std::vector<std::string> solver_names() {
  return registry().names();
}

std::optional<SolverKind> find_solver(std::string_view name) {
  if (auto i = registry().find(name)) return SolverKind(static_cast<int>(*i));
  return std::nullopt;
}

SolverKind solver_named(std::string_view name) {
  return SolverKind(static_cast<int>(registry().index_of(name)));
}

}  // namespace corofem
