#pragma once
// What a solver marks while it runs, for an observer a timed run attaches (in the manner of
// PETSc's log events or Ginkgo's loggers): the numerical classes keep no clocks' totals, no
// counts and no logs, and without an observer their cycles read no clock.
#include "core/name_table.hpp"
#include "linalg/linear_solver.hpp"

namespace corofem {

/// The timed parts of a multigrid solver's life (multigrid/multigrid_solver.hpp).
enum class SolverPart {
  Transfers,        ///< set-up: the hierarchy's transfers (timed by the builder)
  GalerkinStreams,  ///< set-up: the Galerkin method's precomputed streams
  Galerkin,         ///< update: every coarse E = R A R^T
  Smoothers,        ///< update: the smoothers' set-up
  Coarsest,         ///< update: the coarsest level's numeric factorization and its input
  FineSmooth,       ///< solve: the finest level's smoothing
  FineResidual,     ///< solve: the finest level's residual, where the smoothing did not form it
  FineTransfer,     ///< solve: the finest level's restriction and prolongation
  CoarseLevels,     ///< solve: all of the above on the levels between
  CoarsestSolve,    ///< solve: the coarsest level's triangular solves
};

/// Each part's name as a section (core/section_observer.hpp) and in the records: the update's
/// and the solve's parts are keyed apart by the phase they run in ("update/coarsest" is the
/// factorization, "solve/coarsest" its triangular solves).
inline constexpr NameTable<SolverPart, 10> kSolverParts{{{
    {SolverPart::Transfers, "transfers"},
    {SolverPart::GalerkinStreams, "galerkin_streams"},
    {SolverPart::Galerkin, "galerkin"},
    {SolverPart::Smoothers, "smoothers"},
    {SolverPart::Coarsest, "coarsest"},
    {SolverPart::FineSmooth, "fine_smooth"},
    {SolverPart::FineResidual, "fine_residual"},
    {SolverPart::FineTransfer, "fine_transfer"},
    {SolverPart::CoarseLevels, "coarse_levels"},
    {SolverPart::CoarsestSolve, "coarsest"},
}}};

/// Counted, not timed.
enum class SolverEvent {
  Update,          ///< a set_matrix or take_matrix
  DeferredUpdate,  ///< an update whose factorization ran in the next solve
};

/// Receives a solver's marks. A solver never calls it from two threads at once.
class SolverObserver {
 public:
  virtual ~SolverObserver() = default;
  virtual void on_part(SolverPart part, double ms) = 0;
  virtual void on_event(SolverEvent event) = 0;
  virtual void on_solve(const SolveStats& stats) = 0;
};

}  // namespace corofem
