#pragma once
// How much memory a run of a scene needs, from measurements: the check that refuses a mesh this
// machine cannot hold runs before anything is allocated, with the solver the scene asks for.
#include <string>

#include "scene/analysis_settings.hpp"

namespace corofem {

/// Peak bytes of a run of `tets` tets with `solver` (one rank; see require_memory for ranks).
/// Measured as the peak RSS of dynamic runs of a unit box (energy-newton rotations, 3 steps, to
/// 1e-4) at 24.6k, 197k and 664k tets, 2026-12-02: about 80 MB of libraries, then per tet
///   mgpcg, multigrid 1.31-1.35 kB, jacobi-pcg 1.17 kB, petsc-mg 2.64 kB, petsc-gamg 2.44-2.82 kB,
///   hypre-boomeramg 3.42 kB,
/// each rounded up by about 10%; CHOLMOD starts at 190 MB (OpenBLAS's buffers) and its factor
/// grows faster than the mesh (fill of a 3D mesh ~ n^4/3): 1.44 GB at 197k tets, 6.38 GB at 664k,
/// so 115 bytes x tets^4/3 above its start (5-7% above both).
double run_bytes(SolverKind solver, double tets);
/// The rule run_bytes applies, for messages ("1.5 kB per tet for mgpcg").
std::string run_bytes_basis(SolverKind solver);

}  // namespace corofem
