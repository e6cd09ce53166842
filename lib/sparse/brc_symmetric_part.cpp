#include "sparse/brc_symmetric_part.hpp"

#include <stdexcept>

namespace corofem {

BrcSymmetricPart::BrcSymmetricPart(const BrcMatrix& pattern) : part_(pattern) {
  transposed_.resize(pattern.col_index.size());
  for (int i = 0; i < pattern.block_rows; ++i)
    for (int k = pattern.row_start[i]; k < pattern.row_start[i + 1]; ++k) {
      const int t = pattern.find(pattern.col_index[k], i);
      if (t < 0) {
        transposed_.clear();
        return;
      }
      transposed_[k] = t;
    }
}

const BrcMatrix& BrcSymmetricPart::of(const BrcMatrix& a) {
  if (!pattern_symmetric())
    throw std::logic_error("BrcSymmetricPart: the pattern is not symmetric");
  for (std::size_t k = 0; k < transposed_.size(); ++k)
    part_.block(static_cast<int>(k)) =
        0.5 * (a.block(static_cast<int>(k)) + a.block(transposed_[k]).transpose());
  return part_;
}

}  // namespace corofem
