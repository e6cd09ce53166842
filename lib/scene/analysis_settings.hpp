#pragma once
// The scene's `analysis` choices that are not a numerical component's own (those keep their
// tables or registries beside the component: the rotation methods, the solvers, kGalerkinMethods,
// kHierarchyKinds, the smoothers): one enum and one name table each, used to parse and to write;
// and what follows from a solver's traits.
#include "core/name_table.hpp"
#include "scene/solver_kind.hpp"

namespace corofem {

enum class AnalysisType { Static, Dynamic };
inline constexpr NameTable<AnalysisType, 2> kAnalysisTypes{{{
    {AnalysisType::Static, "static"},
    {AnalysisType::Dynamic, "dynamic"},
}}};

enum class Formulation { Linear, Corotational };
inline constexpr NameTable<Formulation, 2> kFormulations{{{
    {Formulation::Linear, "linear"},
    {Formulation::Corotational, "corotational"},
}}};

/// linear-implicit: one linear solve per step (the paper's scheme; static: the lagged-rotation
/// iterations); newton: fully implicit Euler / static Newton with the consistent tangent.
enum class Integrator { LinearImplicit, Newton };
inline constexpr NameTable<Integrator, 2> kIntegrators{{{
    {Integrator::LinearImplicit, "linear-implicit"},
    {Integrator::Newton, "newton"},
}}};

/// Where a dynamic linearly implicit step's iterative solve starts: the last two velocities
/// extrapolated linearly, or the projection on the last `start_history` of them
/// (linalg/projected_start.hpp).
enum class SolveStart { Extrapolation, Projection };
inline constexpr NameTable<SolveStart, 2> kSolveStarts{{{
    {SolveStart::Extrapolation, "extrapolation"},
    {SolveStart::Projection, "projection"},
}}};

/// Solvers that run on corofem's hierarchy (petsc-mg: PETSc's PCMG on it).
inline bool is_multigrid_solver(SolverKind solver) {
  return solver.traits().multigrid;
}

/// Solvers that build corofem's hierarchy, and so read the scene's multigrid settings: the
/// multigrid solvers and auto (one of its candidates is MG-PCG).
inline bool builds_hierarchy(SolverKind solver) {
  return solver.traits().builds_hierarchy;
}

/// Solvers through PETSc (and hypre): the ones that distribute their solves under mpirun.
inline bool is_petsc_solver(SolverKind solver) {
  return solver.traits().petsc.has_value();
}

/// Whether `ranks` MPI ranks run a scene of this analysis on a distributed mesh (each rank holding
/// its part: scene/scene_simulation.hpp): a dynamic linearly implicit run or a static one (lagged
/// or Newton, its tangent by the PETSc solver's GMRES) on a PETSc solver. Dynamic Newton runs (a
/// serial sparse factorization) are refused under mpirun when corotational (cli/commands.cpp);
/// linear ones build the whole mesh on every rank, PETSc distributing only the solve.
inline bool distributes_mesh(AnalysisType type, Integrator integrator, SolverKind solver,
                             int ranks) {
  return ranks > 1 && (type == AnalysisType::Static || integrator != Integrator::Newton) &&
         is_petsc_solver(solver);
}

/// Whether a run's Newton tangent goes to its solver instead of the serial sparse factorizations:
/// static corotated Newton on a PETSc solver (its GMRES, on one process or over ranks) or on
/// corofem's multigrid (flexible GMRES preconditioned by it on the tangent's symmetric part: the
/// corotated tangent is not symmetric, so the multigrid's CG does not take it itself). Dynamic
/// Newton's line search on a potential needs its Cholesky.
inline bool newton_tangent_by_solver(AnalysisType type, Integrator integrator,
                                     Formulation formulation, SolverKind solver) {
  return type == AnalysisType::Static && integrator == Integrator::Newton &&
         formulation == Formulation::Corotational &&
         (is_petsc_solver(solver) || solver.traits().preconditions_gmres);
}

/// How a run solves a Newton tangent: none (no corotated Newton), factored (the serial sparse
/// factorizations) or by GMRES on its solver (newton_tangent_by_solver).
enum class NewtonTangent { None, Factored, ByGmres };
inline NewtonTangent newton_tangent(AnalysisType type, Integrator integrator,
                                    Formulation formulation, SolverKind solver) {
  if (newton_tangent_by_solver(type, integrator, formulation, solver))
    return NewtonTangent::ByGmres;
  return integrator == Integrator::Newton && formulation == Formulation::Corotational
             ? NewtonTangent::Factored
             : NewtonTangent::None;
}

}  // namespace corofem
