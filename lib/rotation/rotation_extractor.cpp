#include "rotation/rotation_extractor.hpp"

#include <stdexcept>

#include "rotation/energy_rotation.hpp"
#include "rotation/gram_schmidt_frame.hpp"
#include "rotation/mueller2016.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/smoothed_polar.hpp"
#include "rotation/svd_rotation.hpp"

namespace corofem {

std::unique_ptr<RotationExtractor> make_rotation_extractor(RotationMethod method,
                                                           const TetMesh& mesh,
                                                           const RotationParams& params) {
  switch (method) {
    case RotationMethod::EnergyNewton:
      return std::make_unique<EnergyNewtonExtractor>(mesh, params);
    case RotationMethod::EnergyExact:
      return std::make_unique<EnergyExactExtractor>(mesh);
    case RotationMethod::Polar:
      return std::make_unique<PolarExtractor>(mesh);
    case RotationMethod::PolarFixed:
      return std::make_unique<InversionAwareSvdExtractor>(mesh);
    case RotationMethod::PolarSmoothed:
      return std::make_unique<SmoothedPolarExtractor>(mesh, params);
    case RotationMethod::Qr:
      return std::make_unique<GramSchmidtFrameExtractor>(mesh);
    case RotationMethod::Mueller2016:
      return std::make_unique<Mueller2016Extractor>(mesh, params);
    case RotationMethod::None:
      return std::make_unique<IdentityExtractor>();
  }
  throw std::logic_error("make_rotation_extractor: unhandled method");
}

}  // namespace corofem
