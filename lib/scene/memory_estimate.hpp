#pragma once
// How much memory a run of a scene needs, from measurements: the check that refuses a mesh this
// machine cannot hold runs before anything is allocated, with the solver the scene asks for.
#include <string>

#include "scene/analysis_settings.hpp"

namespace corofem {

/// Peak bytes of a run of `tets` tets with `solver` on one rank, or per rank of `ranks` on a
/// distributed mesh (analysis_settings.hpp: distributes_mesh).
/// Measured as the peak RSS of dynamic runs (energy-newton rotations, 3 steps, to 1e-4): about
/// 80 MB of libraries, then per tet
///   mgpcg, multigrid 1.31-1.35 kB, jacobi-pcg 1.17 kB (a unit box at 24.6k, 197k and 664k tets);
///   petsc-mg 1.55-1.66 kB, petsc-gamg 1.60-1.71 kB, hypre-boomeramg 2.72-2.79 kB (bars of 207k
///   and 415k tets, the matrix's values written into PETSc's arrays without COO maps), each rounded
///   up by about 10% (GAMG by 17%: at 2 ranks it needs 1.48 kB per tet of its share over the
///   libraries); CHOLMOD starts at 190 MB (OpenBLAS's buffers) and its factor
/// grows faster than the mesh (fill of a 3D mesh ~ n^4/3): 1.44 GB at 197k tets, 6.38 GB at 664k,
/// so 115 bytes x tets^4/3 above its start (5-7% above both).
/// Distributed: the libraries, then the larger of the whole body rank 0 builds before it sends
/// the parts (150 bytes per tet: the mesh, materials, loads; measured 92) and the solver's
/// bytes per tet over its share of the tets, 1.3x for the halo (the largest rank of a 415k-tet bar
/// held 1.04x its share at 2 ranks, 1.22x at 4; peak RSS per rank 504 and 321 MB for petsc-mg,
/// against 579 and 330 MB estimated; GAMG 614 MB at 2 ranks against 619).
/// `tangent`: how a corotated Newton run solves its tangent. Factored (CHOLMOD's rule: Cholesky,
/// GMRES on a Cholesky factor, or UMFPACK's LU; a 240k-tet static bar peaked at 1593 MB, the rule
/// gives 1.9 GB); by the PETSc solver's GMRES (scene/analysis_settings.hpp:
/// newton_tangent_by_solver), whose 50 basis vectors add 300 bytes per tet (3 DOFs on about 0.2
/// vertices per tet; GAMG's Newton on that bar at 2 ranks peaked at 391 MB a rank, against 439 MB
/// estimated with them); by corofem's flexible GMRES on the multigrid, 900 bytes per tet (its
/// basis of up to 100 vectors, the tangent's symmetric part and the definite stand-in: the bar on
/// mgpcg peaked at 463 MB, in 6-7 GMRES iterations a tangent, against 656 MB estimated).
double run_bytes(SolverKind solver, double tets, int ranks = 1,
                 NewtonTangent tangent = NewtonTangent::None);
/// The rule run_bytes applies, for messages ("1.5 kB per tet for mgpcg").
std::string run_bytes_basis(SolverKind solver, int ranks = 1,
                            NewtonTangent tangent = NewtonTangent::None);

}  // namespace corofem
