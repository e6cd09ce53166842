#include "multigrid/multigrid_parts.hpp"

#include <algorithm>

#include "multigrid/solver_part.hpp"

namespace corofem {
namespace {

double ms(const EventLog& log, SolverPart part) {
  return log.ms(kSolverParts.name(part));
}

double mean(double total, int count) {
  return count > 0 ? total / count : 0.0;
}

}  // namespace

bool is_multigrid_solve(const LoggedSolve& solve) {
  return solve.solver == "mgpcg" || solve.solver == "multigrid";
}

MultigridSetupParts setup_parts_ms(const EventLog& log) {
  MultigridSetupParts p;
  p.transfers = ms(log, SolverPart::Transfers);
  p.galerkin_streams = ms(log, SolverPart::GalerkinStreams);
  return p;
}

MultigridUpdateParts update_parts_ms(const EventLog& log) {
  const int n = log.count("update");
  return {mean(ms(log, SolverPart::Galerkin), n), mean(ms(log, SolverPart::Smoothers), n),
          mean(ms(log, SolverPart::Coarsest), n)};
}

MultigridSolveParts solve_parts_ms(const EventLog& log) {
  const auto n = static_cast<int>(std::ranges::count_if(log.solves(), is_multigrid_solve));
  return {mean(ms(log, SolverPart::FineSmooth), n), mean(ms(log, SolverPart::FineResidual), n),
          mean(ms(log, SolverPart::FineTransfer), n), mean(ms(log, SolverPart::CoarseLevels), n),
          mean(ms(log, SolverPart::CoarsestSolve), n)};
}

}  // namespace corofem
