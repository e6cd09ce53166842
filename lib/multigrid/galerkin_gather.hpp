#pragma once
// The Galerkin product E = R A R^T by a gather stream: the pairs of Algorithm 1 (paper section
// 4.3), ordered by their destination block of E instead of by A's blocks. Each block of E sums its
// pairs (R_il R_jk, index of A_lk) in registers and is written once, in storage order. The
// paper's order (GalerkinStream) adds into E's blocks pair by pair, and consecutive blocks of an
// A row share most destinations. Our reading of why that is slower, inferred from the timings
// (these machines have no counters to confirm it): each add reads a block the one before has
// just stored, a chain through memory rather than through the FMA units.
// Within a block the pairs keep A's storage order, the order in which the stream adds them: both
// compute the same sums in the same order, so E is the same bits as the symmetric stream's in the
// same kernel form, at any thread count.
#include <cstdint>
#include <vector>

#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

class GalerkinGather {
 public:
#pragma pack(push, 1)
  struct Pair {
    double weight;
    std::uint32_t source;  ///< block index in A
  };
#pragma pack(pop)

  GalerkinGather() = default;
  /// For symmetric A (every system matrix here): the blocks E_ij, i <= j, are summed and E_ji =
  /// E_ij^T mirrored. `parts` ranges of E's rows, one per thread (0: thread_count()), balanced by
  /// pair counts.
  GalerkinGather(const BrcMatrix& a, const Transfer& t, const BrcMatrix& e, int parts = 0);
  /// E = R A R^T (every block of E is written; A must have the pattern the stream was built for).
  void apply(const BrcMatrix& a, BrcMatrix& e) const;

  std::size_t num_pairs() const {
    return pairs_.size();
  }
  std::size_t bytes() const;  ///< the pairs, the summed blocks' indices and their pair offsets

 private:
  std::vector<std::uint32_t> blocks_;  ///< E's blocks summed (i <= j), in storage order
  std::vector<std::uint32_t> start_;   ///< pairs of blocks_[u]: [start_[u], start_[u + 1])
  std::vector<Pair> pairs_;
  std::vector<std::size_t>
      part_start_;  ///< blocks_ of part p: [part_start_[p], part_start_[p + 1])
  std::vector<std::pair<std::uint32_t, std::uint32_t>> mirror_;  ///< (E_ij, E_ji) blocks, i < j
};

}  // namespace corofem
