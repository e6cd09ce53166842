#pragma once
// The scene's `analysis.solver` as a LinearSolver for a problem.
#include "fem/fe_problem.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "scene/scene.hpp"

namespace corofem {

/// Multigrid parameters from the scene's analysis keys.
MultigridParams multigrid_params(const AnalysisSpec& analysis);

/// cholmod, multigrid or mgpcg for the problem's pattern, rest positions and supports.
std::unique_ptr<LinearSolver> make_linear_solver(const AnalysisSpec& analysis, const FeProblem& problem);

/// Per vertex: 1 if all three DOFs are fixed.
std::vector<char> fixed_vertices(const DirichletConditions& bc);

}  // namespace corofem
