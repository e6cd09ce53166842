#include "multigrid/hierarchy.hpp"

namespace corofem {

MultigridHierarchy::MultigridHierarchy(const BrcMatrix& fine_pattern,
                                       const std::vector<Vec3>& fine_points,
                                       const std::vector<char>& fixed, double first_cell,
                                       int levels) {
  matrices_.push_back(fine_pattern);
  std::vector<Vec3> points = fine_points;
  std::vector<char> level_fixed = fixed;
  double cell = first_cell;
  for (int h = 1; h < levels; ++h) {
    CoarseLevel coarse = make_lattice_level(points, level_fixed, cell);
    if (coarse.transfer.coarse == 0) break;  // nothing left to coarsen
    matrices_.push_back(galerkin_pattern(matrices_.back(), coarse.transfer));
    streams_.emplace_back(matrices_[h - 1], coarse.transfer, matrices_[h]);
    reuse_.push_back(std::make_unique<GalerkinReuse>(coarse.transfer.coarse));
    transfers_.push_back(std::move(coarse.transfer));
    points = std::move(coarse.points);
    level_fixed.clear();  // coarse levels have no fixed vertices
    cell *= 2;
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
