#pragma once
// The parts of a multigrid solver's life, as the sections it marks for the observers a run
// attaches (core/event_observer.hpp) and as the records name them.
#include "core/name_table.hpp"

namespace corofem {

/// The parts of a multigrid solver's life (multigrid/multigrid_solver.hpp).
enum class SolverPart {
  Transfers,        ///< set-up: the hierarchy's transfers (marked by its maker)
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

/// Each part's name as a section, one each: the coarsest level's factorization (the update's)
/// and its triangular solves (the solve's) apart.
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
    {SolverPart::CoarsestSolve, "coarsest_solve"},
}}};

}  // namespace corofem
