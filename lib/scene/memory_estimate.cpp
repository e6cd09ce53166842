#include "scene/memory_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "core/number_text.hpp"

namespace corofem {

namespace {

/// The process before its mesh: libraries, PETSc, MPI; 80 MB with gmsh loaded (the rank that
/// meshes), 44-48 without (gmsh is loaded at its first call): kept at the larger.
constexpr double kLibraryBytes = 80e6;
/// CHOLMOD's start (OpenBLAS's buffers, its workspace: 196 MB at 24.6k tets against MG-PCG's
/// 109 MB) and its factor's fill, bytes x tets^(4/3).
constexpr double kCholmodBytes = 190e6, kCholmodFill = 115;
/// Distributed: the whole body rank 0 builds first, and the largest rank's tets over its share.
constexpr double kWholeBodyBytesPerTet = 150, kHaloFactor = 1.3;
/// Bytes per tet of a run on `solver` whose memory grows with the mesh (its traits'), with
/// Newton's GMRES where the tangent is solved by it: PETSc's basis (50 vectors of 3 DOFs on about
/// 0.2 vertices per tet), or corofem's flexible GMRES on the multigrid
/// (integrate/preconditioned_gmres_solve.hpp: its basis of at most 2 x 50 vectors and two more
/// matrices of the stiffness's pattern).
double bytes_per_tet(SolverKind solver, NewtonTangent tangent) {
  const SolverTraits& t = solver.traits();
  return t.bytes_per_tet + (tangent == NewtonTangent::ByGmres ? t.gmres_bytes_per_tet : 0);
}

}  // namespace

double run_bytes(SolverKind solver, double tets, int ranks, NewtonTangent tangent) {
  if (solver.traits().factorizes || tangent == NewtonTangent::Factored)
    return kCholmodBytes + kCholmodFill * std::pow(tets, 4.0 / 3);
  const double per_tet = bytes_per_tet(solver, tangent);
  if (ranks > 1)
    return kLibraryBytes +
           std::max(kWholeBodyBytesPerTet * tets, per_tet * kHaloFactor * tets / ranks);
  return kLibraryBytes + per_tet * tets;
}

std::string run_bytes_basis(SolverKind solver, int ranks, NewtonTangent tangent) {
  if (tangent == NewtonTangent::Factored)
    return "Newton's sparse factorizations: 115 bytes x tets^4/3 (a factor's fill)";
  const std::string name = solver.name();
  if (solver.traits().factorizes) return name + ": 115 bytes x tets^4/3 (its factor's fill)";
  const bool gmres = tangent == NewtonTangent::ByGmres;
  const std::string per_tet = general_number(bytes_per_tet(solver, tangent) / 1e3) + " kB per tet" +
                              (gmres ? " (with Newton's GMRES)" : "");
  if (ranks > 1)
    return name + ": " + per_tet + " over each rank's share of " + std::to_string(ranks) +
           " and its halo, at least 150 bytes per tet of the whole mesh rank 0 builds first";
  return name + ": " + per_tet;
}

}  // namespace corofem
