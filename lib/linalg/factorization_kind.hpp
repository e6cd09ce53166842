#pragma once
// Which numeric factorization CHOLMOD computes (scene key analysis.factorization): chosen by the
// caller, since what pays depends on whether other factorizations run beside it.
#include "core/name_table.hpp"

namespace corofem {

/// CHOLMOD's numeric factorization.
/// - Supernodal: dense blocks by BLAS, the faster on its own (the multigrid's coarsest operator,
///   denser than a mesh's). Its BLAS calls take turns
///   across threads (linalg/blas_turn.hpp), and Debian's CHOLMOD opens OpenMP regions for each
///   supernode, a system call each even when serial.
/// - Simplicial: row by row, no BLAS and no OpenMP: factorizations in threads side by side never
///   wait on each other (the stability study's: lib/docs/report.md).
enum class Factorization { Supernodal, Simplicial };
inline constexpr NameTable<Factorization, 2> kFactorizations{{{
    {Factorization::Supernodal, "supernodal"},
    {Factorization::Simplicial, "simplicial"},
}}};

}  // namespace corofem
