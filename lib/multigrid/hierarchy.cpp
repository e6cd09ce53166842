#include "multigrid/hierarchy.hpp"

namespace corofem {

MultigridHierarchy::MultigridHierarchy(const BrcMatrix& fine_pattern, std::vector<Transfer> transfers)
    : transfers_(std::move(transfers)) {
  matrices_.push_back(fine_pattern);
  for (std::size_t h = 0; h < transfers_.size(); ++h) {
    matrices_.push_back(galerkin_pattern(matrices_[h], transfers_[h]));
    streams_.emplace_back(matrices_[h], transfers_[h], matrices_[h + 1]);
    reuse_.push_back(std::make_unique<GalerkinReuse>(transfers_[h].coarse));
  }
}

void MultigridHierarchy::update(const BrcMatrix& fine, GalerkinMethod method) {
  matrices_[0].values = fine.values;
  for (std::size_t h = 0; h < transfers_.size(); ++h) {
    switch (method) {
      case GalerkinMethod::Naive:
        galerkin_naive(matrices_[h], transfers_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::Stream:
        streams_[h].apply(matrices_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::StreamFull:
        if (full_streams_.size() <= h)
          full_streams_.emplace_back(matrices_[h], transfers_[h], matrices_[h + 1],
                                     GalerkinStream::Symmetry::Full);
        full_streams_[h].apply(matrices_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::Reuse:
        reuse_[h]->apply(matrices_[h], transfers_[h], matrices_[h + 1]);
        break;
    }
  }
}

std::size_t MultigridHierarchy::stream_bytes(GalerkinMethod format) const {
  std::size_t bytes = 0;
  for (const auto& s : format == GalerkinMethod::StreamFull ? full_streams_ : streams_) bytes += s.bytes();
  return bytes;
}

}  // namespace corofem
