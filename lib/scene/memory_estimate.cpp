#include "scene/memory_estimate.hpp"

#include <cmath>

#include "core/number_text.hpp"

namespace corofem {

namespace {

constexpr double kLibraryBytes = 80e6;  ///< the process before its mesh: libraries, PETSc, MPI
/// CHOLMOD's start (OpenBLAS's buffers, its workspace: 196 MB at 24.6k tets against MG-PCG's
/// 109 MB) and its factor's fill, bytes x tets^(4/3).
constexpr double kCholmodBytes = 190e6, kCholmodFill = 115;

/// Bytes per tet of the solvers whose memory grows with the mesh.
double linear_bytes_per_tet(SolverKind solver) {
  switch (solver) {
    case SolverKind::Multigrid:
    case SolverKind::Mgpcg:
      return 1.5e3;
    case SolverKind::JacobiPcg:
      return 1.3e3;
    case SolverKind::PetscMg:
      return 2.9e3;
    case SolverKind::PetscGamg:
      return 3.1e3;
    case SolverKind::HypreBoomeramg:
      return 3.8e3;
    case SolverKind::Cholmod:
      break;
  }
  return 0;
}

}  // namespace

double run_bytes(SolverKind solver, double tets) {
  if (solver == SolverKind::Cholmod) return kCholmodBytes + kCholmodFill * std::pow(tets, 4.0 / 3);
  return kLibraryBytes + linear_bytes_per_tet(solver) * tets;
}

std::string run_bytes_basis(SolverKind solver) {
  const std::string name = kSolverKinds.name(solver);
  if (solver == SolverKind::Cholmod) return name + ": 115 bytes x tets^4/3 (its factor's fill)";
  return name + ": " + general_number(linear_bytes_per_tet(solver) / 1e3) + " kB per tet";
}

}  // namespace corofem
