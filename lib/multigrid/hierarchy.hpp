#pragma once
// A multigrid hierarchy over a fine BRC matrix: given the transfers of every level
// (hierarchy_builder.hpp), the coarse patterns are built once, and each Galerkin method's
// precomputed streams on its first use (a run uses one method; building them all would double
// the set-up's time and memory); update() rebuilds every coarse operator E_{h+1} = R_h A_h R_h^T
// from new fine values.
#include <memory>

#include "multigrid/galerkin.hpp"
#include "multigrid/galerkin_gather.hpp"

namespace corofem {

class MultigridHierarchy {
 public:
  /// `transfers[h]` takes level h to h + 1 (level 0 has the fine pattern's vertices).
  MultigridHierarchy(const BrcMatrix& fine_pattern, std::vector<Transfer> transfers);

  /// Copies the fine values and recomputes every coarse level with the given method.
  void update(const BrcMatrix& fine, GalerkinMethod method = GalerkinMethod::Gather);
  /// The same, the fine values swapped in instead of copied (fine gets the previous ones; its
  /// pattern must be the hierarchy's).
  void take_update(BrcMatrix& fine, GalerkinMethod method = GalerkinMethod::Gather);
  /// take_update's swap of the fine values alone, and update's copy of them alone: the coarse
  /// levels keep their operators (update_coarse recomputes them).
  void take_fine(BrcMatrix& fine);
  void set_fine(const BrcMatrix& fine);
  /// Every E_{h+1} = R_h E_h R_h^T from the current level h, level after level.
  void update_coarse(GalerkinMethod method);

  int num_levels() const { return static_cast<int>(matrices_.size()); }
  const BrcMatrix& matrix(int h) const { return matrices_[h]; }
  BrcMatrix& matrix(int h) { return matrices_[h]; }
  /// Transfer from level h to h + 1.
  const Transfer& transfer(int h) const { return transfers_[h]; }
  /// Builds what `method` precomputes on every level (its streams), so that no update pays for it.
  void prepare(GalerkinMethod method);
  /// Level h's symmetric stream, gather and the paper's full stream, each built on first use.
  /// Not safe to call from two threads at once for a level not yet built: every caller (the
  /// solver's set-up, the update, the roofline, the benchmarks) calls them from one thread.
  const GalerkinStream& stream(int h) const;
  const GalerkinGather& gather(int h) const;
  const GalerkinStream& full_stream(int h) const;
  /// Bytes of all control and data streams of the given method (Gather: the gather's pairs and
  /// block lists; Naive and Reuse precompute none: 0).
  std::size_t stream_bytes(GalerkinMethod method) const;

 private:
  std::vector<BrcMatrix> matrices_;
  std::vector<Transfer> transfers_;
  // Built on first use (hence mutable: the const accessors build them too), one per level.
  mutable std::vector<std::unique_ptr<GalerkinStream>> streams_;       ///< symmetric format
  mutable std::vector<std::unique_ptr<GalerkinStream>> full_streams_;  ///< the paper's format
  mutable std::vector<std::unique_ptr<GalerkinGather>> gathers_;
  std::vector<std::unique_ptr<GalerkinReuse>> reuse_;
};

}  // namespace corofem
