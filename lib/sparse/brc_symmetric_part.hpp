#pragma once
// The symmetric part (A + A^T) / 2 of a BRC matrix whose block pattern is symmetric, on A's own
// pattern. A corotated Newton tangent is such a matrix (its skew part is the rotations'
// derivative); its symmetric part is what a Cholesky factor or an SPD multigrid can precondition.
// Each block's transposed partner is found once, at construction: every later matrix costs one
// pass over the values.
#include <vector>

#include "sparse/brc_matrix.hpp"

namespace corofem {

class BrcSymmetricPart {
 public:
  explicit BrcSymmetricPart(const BrcMatrix& pattern);
  /// False where some block (i, j) of the pattern has no (j, i): then of() may not be called.
  bool pattern_symmetric() const { return !transposed_.empty() || part_.num_blocks() == 0; }
  /// (A + A^T) / 2 for A of the pattern given at construction; the reference stays valid (and is
  /// overwritten) until the next call.
  const BrcMatrix& of(const BrcMatrix& a);

 private:
  BrcMatrix part_;
  std::vector<int> transposed_;  ///< for each block (i, j), the index of block (j, i)
};

}  // namespace corofem
