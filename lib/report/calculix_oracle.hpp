#pragma once
// CalculiX (ccx, Debian's calculix-ccx) as an outside oracle for the model: the same mesh,
// materials, supports and loads as a C3D4 deck, solved linearly or with NLGEOM (total Lagrangian,
// St. Venant-Kirchhoff for *ELASTIC), displacements read back from the .dat file.
#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "fem/fe_problem.hpp"

namespace corofem {

/// True when `ccx` is on PATH.
bool calculix_available();

/// The deck: nodes (tag = vertex + 1), C3D4 elements grouped by material, *BOUNDARY for every fixed
/// DOF with its value, *CLOAD for every nonzero external force component (so the loads are the
/// very vectors corofem uses, not CalculiX's own integration of them), *NODE PRINT of U. With
/// `nlgeom`, the step is geometrically nonlinear with increments of at most 1 / `increments`.
std::string calculix_deck(const FeProblem& problem, bool nlgeom, int increments = 20);

/// Writes the deck to `work_dir`/`job`.inp, runs ccx there on one thread, and returns the
/// displacements of the last increment per DOF. Throws NumericalFault naming the job and the end
/// of ccx's log when ccx fails or prints no displacements for every node.
Eigen::VectorXd run_calculix(const FeProblem& problem, bool nlgeom,
                             const std::filesystem::path& work_dir, const std::string& job,
                             int increments = 20);

}  // namespace corofem
