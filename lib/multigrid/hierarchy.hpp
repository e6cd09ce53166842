#pragma once
// A multigrid hierarchy over a fine BRC matrix: given the transfers of every level
// (hierarchy_builder.hpp), the coarse patterns and Galerkin streams (the symmetric stream and the
// gather) are built once;
// update() rebuilds every coarse operator E_{h+1} = R_h A_h R_h^T from new fine values.
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

  int num_levels() const { return static_cast<int>(matrices_.size()); }
  const BrcMatrix& matrix(int h) const { return matrices_[h]; }
  BrcMatrix& matrix(int h) { return matrices_[h]; }
  /// Transfer from level h to h + 1.
  const Transfer& transfer(int h) const { return transfers_[h]; }
  const GalerkinStream& stream(int h) const { return streams_[h]; }
  const GalerkinGather& gather(int h) const { return gathers_[h]; }
  /// Bytes of all control and data streams of the given format (Gather: the gather streams).
  std::size_t stream_bytes(GalerkinMethod format = GalerkinMethod::Stream) const;

 private:
  void update_coarse(GalerkinMethod method);  ///< every E_{h+1} from the current level h

  std::vector<BrcMatrix> matrices_;
  std::vector<Transfer> transfers_;
  std::vector<GalerkinStream> streams_;       ///< symmetric format
  std::vector<GalerkinStream> full_streams_;  ///< the paper's format, built on first use
  std::vector<std::unique_ptr<GalerkinReuse>> reuse_;
  std::vector<GalerkinGather> gathers_;
};

}  // namespace corofem
