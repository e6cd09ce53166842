#pragma once
// The share of a Galerkin coarse operator E = R A R^T (paper section 4.3, eq. 9) that some of A's
// rows contribute: with the fine vertices split into parts whose rows of A are complete (a
// distributed mesh's part holds every tet of its owned vertices), E = sum over the parts of
// R_{:,own} A_{own,:} R^T. A rank of a distributed petsc-mg run computes its share this way and
// PETSc adds the shares across ranks (solver/petsc_coarse_operators.hpp), in place of PETSc's
// parallel MatPtAP, whose intermediate products (A P on each rank, kept for reuse) made a rank's
// memory at two ranks larger than the whole problem's on one.
#include "multigrid/galerkin.hpp"
#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

class GalerkinRowShare {
 public:
  /// `a`: the pattern of the fine matrix as this part holds it (its local vertex numbering);
  /// `t`: P's rows of every vertex `a` numbers, in that numbering (row l at t.p_start[l]:
  /// rows_of(t, part.global_vertex), or a whole transfer), its coarse vertices the whole level's;
  /// rows [begin, end) of `a`: the share's (complete rows).
  GalerkinRowShare(const BrcMatrix& a, const Transfer& t, int begin, int end);

  /// The share's values from `a` (of the pattern given at construction).
  void apply(const BrcMatrix& a);

  /// The share: coarse x coarse in the coarse level's numbering; rows that none of the share's
  /// fine rows restricts to are empty.
  const BrcMatrix& share() const { return e_; }

 private:
  Transfer t_;  ///< P's rows as given; R's rows built from P's rows [begin, end) alone
  BrcMatrix e_;
  GalerkinReuse reuse_;
};

}  // namespace corofem
