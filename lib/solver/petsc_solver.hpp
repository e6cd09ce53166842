#pragma once
// The algebraic multigrid solvers users would pick instead of ours, through PETSc:
//   petsc-gamg       CG preconditioned by PETSc's smoothed aggregation (GAMG) with the six
//                    rigid-body modes of the rest positions as near null space;
//   hypre-boomeramg  CG preconditioned by hypre's BoomerAMG (PETSc's PCHYPRE) as systems AMG
//                    (unknown approach, 3 functions) with the 3D strong threshold 0.5 of hypre's
//                    manual (why not nodal coarsening or rigid-body interpolation: the .cpp);
//   petsc-mg         CG preconditioned by PETSc's PCMG V-cycle on corofem's own hierarchy: our
//                    P = R^T as interpolation, Galerkin coarse operators (the first level's
//                    from each rank's share of its rows, summed by PETSc; the coarser ones by
//                    MatPtAP: solver/petsc_coarse_operators.hpp), Chebyshev on point Jacobi (degree
//                    2 per `smoothing`) on each level, and LU of the coarsest.
// Each solves to the scene's relative residual |b - A x| / |b| from the initial guess in x, like
// mgpcg; a non-symmetric matrix (static Newton's corotated tangent on a distributed mesh) by
// right-preconditioned GMRES in CG's place. set_matrix copies the values into a PETSc AIJ matrix of
// block size 3 (its pattern built once from the BRC pattern) and sets the preconditioner up: the
// `update` phase of a step. With setup_reuse (scene key analysis.setup_reuse), GAMG keeps its first
// interpolation and recomputes only the coarse operators, BoomerAMG keeps its whole first
// hierarchy. PETSC_OPTIONS in the environment overrides any of these settings (prefixes
// corofem_gamg_, corofem_boomeramg_).
#include <memory>
#include <string>
#include <vector>

#include "core/name_table.hpp"
#include "linalg/linear_solver.hpp"
#include "mesh/rank_part.hpp"
#include "mesh/tet_mesh.hpp"
#include "multigrid/transfer.hpp"

namespace corofem {

enum class PetscSolverKind { Gamg, BoomerAmg, Mg };
/// The solvers' names, as the scene's analysis.solver spells them.
inline constexpr NameTable<PetscSolverKind, 3> kPetscSolverKinds{{{
    {PetscSolverKind::Gamg, "petsc-gamg"},
    {PetscSolverKind::BoomerAmg, "hypre-boomeramg"},
    {PetscSolverKind::Mg, "petsc-mg"},
}}};

/// Whether this build has PETSc (and with it hypre).
bool have_petsc();

/// `nonsymmetric`: GMRES (right-preconditioned, restarted) instead of CG, for a matrix that is
/// not symmetric (static Newton's corotated tangent on a distributed mesh).
/// PetscSolverKind::Mg takes the hierarchy's `transfers` (of the whole mesh), finest first.
/// Throws InputError naming analysis.solver when this build has no PETSc.
/// Replicated (no `part`): matrices and vectors are the whole mesh's on every rank, each rank
/// gives PETSc its owned rows and gets the whole solution back. Distributed (`part`, which must
/// outlive the solver): they are the part's (rest_positions its mesh's), its owned rows are
/// solved for and its halo entries of x are received from their owners (PETSc's ghost update).
std::unique_ptr<LinearSolver> make_petsc_solver(
    PetscSolverKind kind, const std::vector<Vec3>& rest_positions, double tolerance,
    int max_iterations, std::vector<Transfer> transfers = {}, int smoothing = 1,
    bool setup_reuse = false, const RankPart* part = nullptr, bool nonsymmetric = false);

}  // namespace corofem
