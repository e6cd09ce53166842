#pragma once
// The linear solvers a scene names in analysis.solver, and what the rest of corofem needs to know
// of each: one traits record per solver, registered once and found by name, as the rotation
// methods and the smoothers are. The built-ins' records are in scene/solver_registry.cpp beside
// their makers (scene/solver_factory.hpp); a user's program registers its own with
// register_solver before it runs anything, and scenes then name it.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/parameters.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/petsc_solver.hpp"

namespace corofem {

struct AnalysisSpec;
struct FeProblem;
struct TetMesh;
class EventObserver;
struct SolverTraits;

/// A registered solver: its place in the registry. The built-ins have fixed places.
class SolverKind {
 public:
  constexpr explicit SolverKind(int id) : id_(id) {}
  static const SolverKind Cholmod;    ///< CHOLMOD's direct solve (the oracle's library)
  static const SolverKind Multigrid;  ///< V-cycles to the tolerance
  static const SolverKind Mgpcg;      ///< CG preconditioned by a V-cycle (the paper's)
  static const SolverKind JacobiPcg;  ///< CG preconditioned by the block diagonal
  static const SolverKind PetscGamg;  ///< PETSc's smoothed aggregation
  static const SolverKind HypreBoomeramg;
  static const SolverKind PetscMg;  ///< PETSc's PCMG on corofem's hierarchy
  static const SolverKind Auto;     ///< MG-PCG or Jacobi-PCG, the cheaper on the first solves

  constexpr int id() const { return id_; }
  const SolverTraits& traits() const;
  const std::string& name() const;  ///< the scene name
  friend constexpr bool operator==(SolverKind, SolverKind) = default;
  friend constexpr auto operator<=>(SolverKind, SolverKind) = default;

 private:
  int id_;
};
inline constexpr SolverKind SolverKind::Cholmod{0};
inline constexpr SolverKind SolverKind::Multigrid{1};
inline constexpr SolverKind SolverKind::Mgpcg{2};
inline constexpr SolverKind SolverKind::JacobiPcg{3};
inline constexpr SolverKind SolverKind::PetscGamg{4};
inline constexpr SolverKind SolverKind::HypreBoomeramg{5};
inline constexpr SolverKind SolverKind::PetscMg{6};
inline constexpr SolverKind SolverKind::Auto{7};

/// What a solver is made from: the scene's analysis (its tolerance, its multigrid's parameters,
/// the solver's own settings), the problem (its pattern, rest positions and supports), the
/// coarse meshes of a meshes hierarchy, and the observer that hears the solver's marks (the factory
/// hands it to the solver made: LinearSolver::observe).
struct SolverRequest {
  const AnalysisSpec& analysis;
  const FeProblem& problem;
  const std::vector<TetMesh>& coarse_meshes;
  EventObserver* observer = nullptr;
};

struct SolverTraits {
  std::string name{};  ///< the scene's analysis.solver
  std::function<std::unique_ptr<LinearSolver>(const SolverRequest&)> make{};
  /// Its own settings, each a scene key of `analysis` (core/parameters.hpp), read into
  /// AnalysisSpec::solver_parameters for it.
  std::vector<ParameterSpec> parameters{};
  /// Runs on corofem's hierarchy: the scene's levels and hierarchy are its (petsc-mg too).
  bool multigrid = false;
  /// Builds corofem's hierarchy and so reads every multigrid setting (the multigrid solvers, and
  /// auto, whose candidate MG-PCG does).
  bool builds_hierarchy = false;
  /// Through PETSc: distributes its solves under mpirun, and a static corotated Newton run solves
  /// its tangent by its GMRES; which of PETSc's solvers it is.
  std::optional<PetscSolverKind> petsc{};
  /// A static corotated Newton run solves its tangent by corofem's flexible GMRES preconditioned
  /// by it (integrate/preconditioned_gmres_solve.hpp).
  bool preconditions_gmres = false;
  /// The memory estimate (scene/memory_estimate.hpp): bytes per tet, and Newton's GMRES's on top;
  /// a factorization's fill instead where factorizes.
  double bytes_per_tet = 0;
  double gmres_bytes_per_tet = 300;
  bool factorizes = false;
};

/// Adds a solver; its name must be new and it must have a make. Returns its handle.
SolverKind register_solver(SolverTraits traits);
/// Every registered solver, built-ins first, in registration order.
std::vector<SolverKind> solver_kinds();
std::vector<std::string> solver_names();
std::optional<SolverKind> find_solver(std::string_view name);
/// The solver named `name`; std::out_of_range naming the registered ones for another.
SolverKind solver_named(std::string_view name);

}  // namespace corofem
