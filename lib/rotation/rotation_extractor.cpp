#include "rotation/rotation_extractor.hpp"

#include "core/errors.hpp"
#include "rotation/polar_decomposition.hpp"

namespace corofem {

std::vector<std::string> rotation_method_names() { return {"polar", "none"}; }

std::unique_ptr<RotationExtractor> make_rotation_extractor(const std::string& name,
                                                           const TetMesh& mesh) {
  if (name == "polar") return std::make_unique<PolarExtractor>(mesh);
  if (name == "none") return std::make_unique<IdentityExtractor>();
  std::string known;
  for (const auto& n : rotation_method_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("analysis.rotation: unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace corofem
