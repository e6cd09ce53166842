#include "multigrid/hierarchy.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/threads.hpp"

namespace corofem {

MultigridHierarchy::MultigridHierarchy(const BrcMatrix& fine_pattern,
                                       std::vector<Transfer> transfers)
    : transfers_(std::move(transfers)) {
  matrices_.push_back(fine_pattern);
  for (std::size_t h = 0; h < transfers_.size(); ++h) {
    matrices_.push_back(galerkin_pattern(matrices_[h], transfers_[h]));
    reuse_.push_back(std::make_unique<GalerkinReuse>(transfers_[h].coarse));
  }
  streams_.resize(transfers_.size());
  full_streams_.resize(transfers_.size());
  gathers_.resize(transfers_.size());
}

namespace {

/// slot's object, made from (A_h, R_h, E_{h+1}, extra...) the first time it is asked for.
template <class T, class... Extra>
const T& built(std::unique_ptr<T>& slot, const BrcMatrix& a, const Transfer& t, const BrcMatrix& e,
               Extra... extra) {
  if (!slot) slot = std::make_unique<T>(a, t, e, extra...);
  return *slot;
}

}  // namespace

const GalerkinStream& MultigridHierarchy::stream(int h) const {
  return built(streams_[h], matrices_[h], transfers_[h], matrices_[h + 1]);
}

const GalerkinStream& MultigridHierarchy::full_stream(int h) const {
  return built(full_streams_[h], matrices_[h], transfers_[h], matrices_[h + 1],
               GalerkinStream::Symmetry::Full);
}

const GalerkinGather& MultigridHierarchy::gather(int h) const {
  return built(gathers_[h], matrices_[h], transfers_[h], matrices_[h + 1]);
}

void MultigridHierarchy::update(const BrcMatrix& fine, GalerkinMethod method) {
  set_fine(fine);
  update_coarse(method);
}

void MultigridHierarchy::set_fine(const BrcMatrix& fine) {
  // The fine values copied in, on the threads (a pass at memory speed: 14 MB on the dragon).
  const std::ptrdiff_t values = static_cast<std::ptrdiff_t>(fine.values.size());
  matrices_[0].values.resize(fine.values.size());
  const double* from = fine.values.data();
  double* to = matrices_[0].values.data();
  constexpr std::ptrdiff_t kChunk = 1 << 15;
#pragma omp parallel for schedule(static) num_threads(threads_for(values / 9, LoopItems::Blocks))
  for (std::ptrdiff_t c = 0; c < values; c += kChunk)
    std::copy(from + c, from + std::min(values, c + kChunk), to + c);
}

void MultigridHierarchy::take_update(BrcMatrix& fine, GalerkinMethod method) {
  take_fine(fine);
  update_coarse(method);
}

void MultigridHierarchy::take_fine(BrcMatrix& fine) {
  if (fine.values.size() != matrices_[0].values.size() ||
      fine.block_rows != matrices_[0].block_rows)
    throw std::logic_error("MultigridHierarchy::take_update: the matrix has another pattern");
  std::swap(fine.values, matrices_[0].values);
}

void MultigridHierarchy::update_coarse(GalerkinMethod method) {
  for (std::size_t h = 0; h < transfers_.size(); ++h) {
    switch (method) {
      case GalerkinMethod::Naive:
        galerkin_naive(matrices_[h], transfers_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::Stream:
        stream(static_cast<int>(h)).apply(matrices_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::StreamFull:
        full_stream(static_cast<int>(h)).apply(matrices_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::Gather:
        gather(static_cast<int>(h)).apply(matrices_[h], matrices_[h + 1]);
        break;
      case GalerkinMethod::Reuse:
        reuse_[h]->apply(matrices_[h], transfers_[h], matrices_[h + 1]);
        break;
    }
  }
}

std::size_t MultigridHierarchy::stream_bytes(GalerkinMethod method) const {
  // Asking for a level's stream builds it: prepare() is this sum with the result unused.
  std::size_t bytes = 0;
  for (int h = 0; h + 1 < num_levels(); ++h) {
    if (method == GalerkinMethod::Gather) bytes += gather(h).bytes();
    if (method == GalerkinMethod::Stream) bytes += stream(h).bytes();
    if (method == GalerkinMethod::StreamFull) bytes += full_stream(h).bytes();
  }
  return bytes;
}

void MultigridHierarchy::prepare(GalerkinMethod method) {
  static_cast<void>(stream_bytes(method));
}

}  // namespace corofem
