#include "multigrid/multigrid_log.hpp"

namespace corofem {
namespace {

double mean(double total, std::size_t count) {
  return count > 0 ? total / static_cast<double>(count) : 0.0;
}

}  // namespace

void MultigridLog::on_part(SolverPart part, double ms) {
  switch (part) {
    case SolverPart::Transfers:
      setup_.transfers += ms;
      break;
    case SolverPart::GalerkinStreams:
      setup_.galerkin_streams += ms;
      break;
    case SolverPart::Galerkin:
      update_.galerkin += ms;
      break;
    case SolverPart::Smoothers:
      update_.smoothers += ms;
      break;
    case SolverPart::Coarsest:
      update_.coarsest += ms;
      break;
    case SolverPart::FineSmooth:
      solve_.fine_smooth += ms;
      break;
    case SolverPart::FineResidual:
      solve_.fine_residual += ms;
      break;
    case SolverPart::FineTransfer:
      solve_.fine_transfer += ms;
      break;
    case SolverPart::CoarseLevels:
      solve_.coarse_levels += ms;
      break;
    case SolverPart::CoarsestSolve:
      solve_.coarsest += ms;
      break;
  }
}

void MultigridLog::on_event(SolverEvent event) {
  if (event == SolverEvent::Update) ++updates_;
  if (event == SolverEvent::DeferredUpdate) ++deferred_updates_;
}

void MultigridLog::on_solve(const SolveStats& stats) {
  solves_.push_back(stats);
}

MultigridUpdateParts MultigridLog::update_parts_ms() const {
  const auto n = static_cast<std::size_t>(updates_);
  return {mean(update_.galerkin, n), mean(update_.smoothers, n), mean(update_.coarsest, n)};
}

MultigridSolveParts MultigridLog::solve_parts_ms() const {
  const std::size_t n = solves_.size();
  return {mean(solve_.fine_smooth, n), mean(solve_.fine_residual, n), mean(solve_.fine_transfer, n),
          mean(solve_.coarse_levels, n), mean(solve_.coarsest, n)};
}

}  // namespace corofem
