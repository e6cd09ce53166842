#pragma once
// Galerkin coarse operators E = R A R^T on BRC matrices (paper section 4.3). A block of E is a sum
// of (scalar weight) x (3x3 block of A), since R = Rs (x) I3. Five ways to compute the values of
// E's precomputed pattern (GalerkinMethod below), all proven equal to the oracles in reference/:
//  - naive: eq. (9) entry by entry of E, intersecting the sorted index sets S_l^A and S_j^R;
//  - stream-full: Algorithm 1 as the paper has it, a control and a data stream aligned with A's
//    blocks (GalerkinStream, Symmetry::Full);
//  - stream: the same streams over A's upper triangle, E's lower blocks mirrored (Symmetric);
//  - reuse: the row-wise triple product of production AMG codes writing into E's known pattern
//    through a marker array (the stronger baseline);
//  - gather: the stream's pairs sorted by destination, so each E block is summed in registers
//    and written once (galerkin_gather.hpp; the default).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/name_table.hpp"
#include "multigrid/transfer.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

/// Block pattern of R A R^T (values zero).
BrcMatrix galerkin_pattern(const BrcMatrix& a, const Transfer& t);

/// Eq. (9): E_ij = sum_{l in S_i^R} R_il sum_{k in S_l^A cap S_j^R} A_lk R_jk.
void galerkin_naive(const BrcMatrix& a, const Transfer& t, BrcMatrix& e);

/// Row-wise triple product into E's pattern, a marker array mapping column j to its slot.
class GalerkinReuse {
 public:
  explicit GalerkinReuse(int coarse) : slot_(coarse, -1) {}
  void apply(const BrcMatrix& a, const Transfer& t, BrcMatrix& e);

 private:
  std::vector<int> slot_;
};

/// Visits the pairs of Algorithm 1 in A's storage order: f(b, i, j, R_il R_jk) for every block
/// b = A_lk and coarse vertices i of l and j of k (upper_only: those with i <= j).
template <class F>
void for_each_galerkin_pair(const BrcMatrix& a, const Transfer& t, bool upper_only, const F& f) {
  for (int l = 0; l < a.block_rows; ++l)
    for (int b = a.row_start[l]; b < a.row_start[l + 1]; ++b) {
      const int k = a.col_index[b];
      for (int m = t.p_start[l]; m < t.p_start[l + 1]; ++m)
        for (int n = t.p_start[k]; n < t.p_start[k + 1]; ++n)
          if (!upper_only || t.p_col[n] >= t.p_col[m])
            f(b, t.p_col[m], t.p_col[n], t.p_weight[m] * t.p_weight[n]);
    }
}

/// The (E_ij, E_ji) block pairs, i < j, of a symmetric pattern (see galerkin_mirror_pairs).
using MirrorPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// Algorithm 1. Built once per hierarchy (R does not change). Control stream: one byte per block
/// of A in storage order, top bit 1 = advance to the next block of A, low 7 bits = number p
/// (0..127) of (weight, destination) pairs to process with it; a block scattered more than 127
/// times gets continuation bytes with the top bit 0. Data stream: the pairs (R_il R_jk, index of
/// block E_ij). The numeric phase is one sequential pass; only the writes into E scatter.
/// Threads: E's rows are split into ranges of about equal pair counts, and each range gets its
/// own control and data stream (the paper's format, holding only the pairs whose destination
/// lies in the range). A thread reads its control stream (one byte per block of A) and only the
/// blocks of A it has pairs for, and writes only its rows of E: no two threads write one block,
/// and every block of E sums its pairs in A's storage order, so E is bit-identical at any count.
class GalerkinStream {
 public:
#pragma pack(push, 1)
  struct Pair {
    double weight;
    std::uint32_t destination;  ///< block index in E
  };
#pragma pack(pop)

  /// Full: every pair, as the paper. Symmetric: for symmetric A (every system matrix here), only
  /// the pairs with destination E_ij, i <= j, are streamed (half the pairs and scattered writes);
  /// apply() then mirrors E_ji = E_ij^T.
  enum class Symmetry { Full, Symmetric };

  GalerkinStream() = default;
  /// `parts` streams, one per thread (0: thread_count()).
  GalerkinStream(const BrcMatrix& a, const Transfer& t, const BrcMatrix& e,
                 Symmetry symmetry = Symmetry::Symmetric, int parts = 0);
  /// E = R A R^T (E is zeroed first; A must have the pattern the stream was built for).
  void apply(const BrcMatrix& a, BrcMatrix& e) const;

  std::size_t num_pairs() const;
  std::size_t bytes() const;  ///< every part's control and data streams
  int parts() const {
    return static_cast<int>(parts_.size());
  }
  const std::vector<std::uint8_t>& control(int part = 0) const {
    return parts_[part].control;
  }

 private:
  struct Part {
    int row_lo = 0, row_hi = 0;  ///< the rows of E this part writes
    std::vector<std::uint8_t> control;
    std::vector<Pair> data;
  };
  std::vector<Part> parts_;
  MirrorPairs mirror_;
};

/// The (E_ij, E_ji) block pairs, i < j, of a symmetric pattern: the blocks a symmetric product
/// writes by mirroring.
MirrorPairs galerkin_mirror_pairs(const BrcMatrix& e);
/// E_ji = E_ij^T for every pair of `mirror`. Called inside the caller's parallel region, whose
/// threads share the pairs (an orphaned omp for, with its barrier); outside one, on one thread.
void mirror_blocks(const MirrorPairs& mirror, double* ev);

/// The methods, and their names in scenes and records: "stream" is the symmetric format,
/// "stream-full" the paper's, "gather" the stream's pairs by destination (galerkin_gather.hpp).
enum class GalerkinMethod { Naive, Stream, StreamFull, Reuse, Gather };
inline constexpr NameTable<GalerkinMethod, 5> kGalerkinMethods{
    {{{GalerkinMethod::Naive, "naive"},
      {GalerkinMethod::Stream, "stream"},
      {GalerkinMethod::StreamFull, "stream-full"},
      {GalerkinMethod::Reuse, "reuse"},
      {GalerkinMethod::Gather, "gather"}}}};

}  // namespace corofem
