#pragma once
// The scene's `analysis.solver` as a LinearSolver for a problem.
#include "fem/fe_problem.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// Multigrid parameters from the scene's analysis keys.
MultigridParams multigrid_params(const AnalysisSpec& analysis);

/// The analysis's solver for the problem's pattern, rest positions and supports. Multigrid on the
/// meshes hierarchy takes its levels from `coarse_meshes` (scene/coarse_meshes.hpp).
std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& analysis,
                                                 const FeProblem& problem,
                                                 const std::vector<TetMesh>& coarse_meshes = {});

/// Multigrid (V-cycles, or the preconditioner of CG) on the analysis's hierarchy.
std::unique_ptr<MultigridSolver> make_multigrid_solver(const AnalysisSpec& analysis,
                                                       const FeProblem& problem,
                                                       const std::vector<TetMesh>& coarse_meshes,
                                                       bool as_preconditioner);

/// Per vertex: 1 if all three DOFs are fixed.
std::vector<char> fixed_vertices(const DirichletConditions& bc);

}  // namespace corofem
