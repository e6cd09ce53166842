#include "rotation/rotation_extractor.hpp"

#include "core/errors.hpp"
#include "rotation/energy_rotation.hpp"
#include "rotation/gram_schmidt_frame.hpp"
#include "rotation/mueller2016.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/smoothed_polar.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {

std::vector<std::string> rotation_method_names() {
  return {"energy-newton",  "energy-exact", "polar",       "polar-fixed",
          "polar-smoothed", "qr",           "mueller2016", "none"};
}

std::unique_ptr<RotationExtractor> make_rotation_extractor(const std::string& name,
                                                           const TetMesh& mesh,
                                                           const RotationParams& params) {
  if (name == "energy-newton") return std::make_unique<EnergyNewtonExtractor>(mesh, params);
  if (name == "energy-exact") return std::make_unique<EnergyExactExtractor>(mesh);
  if (name == "polar") return std::make_unique<PolarExtractor>(mesh);
  if (name == "polar-fixed") return std::make_unique<InversionAwareSvdExtractor>(mesh);
  if (name == "polar-smoothed") return std::make_unique<SmoothedPolarExtractor>(mesh, params);
  if (name == "qr") return std::make_unique<GramSchmidtFrameExtractor>(mesh);
  if (name == "mueller2016") return std::make_unique<Mueller2016Extractor>(mesh, params);
  if (name == "none") return std::make_unique<IdentityExtractor>();
  std::string known;
  for (const auto& n : rotation_method_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("analysis.rotation: unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace corofem
