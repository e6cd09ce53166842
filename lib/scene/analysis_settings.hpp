#pragma once
// The scene's `analysis` choices that are not a numerical component's own (those keep their
// tables or registries beside the component: the rotation methods, kGalerkinMethods,
// kHierarchyKinds, the smoothers): one enum and one name table each, used to parse and to write.
#include "core/name_table.hpp"
#include "solver/petsc_solver.hpp"

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

/// auto: the run's first solves measure mgpcg and jacobi-pcg on the scene and keep the cheaper
/// (linalg/solver_choice.hpp).
enum class SolverKind {
  Cholmod,
  Multigrid,
  Mgpcg,
  JacobiPcg,
  PetscGamg,
  HypreBoomeramg,
  PetscMg,
  Auto
};
inline constexpr NameTable<SolverKind, 8> kSolverKinds{{{
    {SolverKind::Cholmod, "cholmod"},
    {SolverKind::Multigrid, "multigrid"},
    {SolverKind::Mgpcg, "mgpcg"},
    {SolverKind::JacobiPcg, "jacobi-pcg"},
    {SolverKind::PetscGamg, "petsc-gamg"},
    {SolverKind::HypreBoomeramg, "hypre-boomeramg"},
    {SolverKind::PetscMg, "petsc-mg"},
    {SolverKind::Auto, "auto"},
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
  return solver == SolverKind::Multigrid || solver == SolverKind::Mgpcg ||
         solver == SolverKind::PetscMg;
}

/// Solvers that build corofem's hierarchy, and so read the scene's multigrid settings: the
/// multigrid solvers and auto (one of its candidates is MG-PCG).
inline bool builds_hierarchy(SolverKind solver) {
  return is_multigrid_solver(solver) || solver == SolverKind::Auto;
}

/// The algebraic multigrid of the libraries, whose setup can be reused across steps
/// (analysis.setup_reuse).
inline bool is_library_amg(SolverKind solver) {
  return solver == SolverKind::PetscGamg || solver == SolverKind::HypreBoomeramg;
}

/// Solvers through PETSc (and hypre): the ones that distribute their solves under mpirun.
inline bool is_petsc_solver(SolverKind solver) {
  return is_library_amg(solver) || solver == SolverKind::PetscMg;
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
         (is_petsc_solver(solver) || is_multigrid_solver(solver));
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

/// The PETSc solver of a solver kind for which is_petsc_solver holds.
inline PetscSolverKind petsc_solver_kind(SolverKind solver) {
  return solver == SolverKind::PetscGamg        ? PetscSolverKind::Gamg
         : solver == SolverKind::HypreBoomeramg ? PetscSolverKind::BoomerAmg
                                                : PetscSolverKind::Mg;
}

}  // namespace corofem
