#include "rotation/rotation_extractor.hpp"

#include <stdexcept>

namespace corofem {

std::unique_ptr<RotationExtractor> make_rotation_extractor(RotationMethod method,
                                                           const TetMesh& mesh,
                                                           const RotationParams& params) {
  std::unique_ptr<RotationExtractor> extractor = method.traits().make(mesh, params);
  if (!extractor || extractor->method() != method)
    throw std::logic_error("rotation method '" + method.name() +
                           "': its make builds no extractor of that method");
  return extractor;
}

}  // namespace corofem
