#include "linalg/blas_turn.hpp"

namespace corofem {

std::unique_lock<std::mutex> take_blas_turn() {
  static std::mutex turn;
  return std::unique_lock<std::mutex>(turn);
}

}  // namespace corofem
