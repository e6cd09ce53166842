#include "rotation/rotation_extractor.hpp"

#include <stdexcept>

namespace corofem {

std::unique_ptr<RotationExtractor> make_rotation_extractor(RotationMethod method,
                                                           const TetMesh& mesh,
                                                           const Parameters& params) {
  const RotationMethodTraits& traits = method.traits();
  Parameters own(traits.parameters);  // its defaults, then what `params` gives of its own
  for (const ParameterSpec& spec : traits.parameters)
    if (params.has(spec.key)) own.set(spec.key, params.values().find(spec.key)->second);
  std::unique_ptr<RotationExtractor> extractor = traits.make(mesh, own);
  if (!extractor || extractor->method() != method)
    throw std::logic_error("rotation method '" + method.name() +
                           "': its make builds no extractor of that method");
  return extractor;
}

}  // namespace corofem
