// A rotation method of one's own: the paper's energy (eq. 3) minimized by Mueller et al. 2016's
// iteration on the element's moment S = F C instead of on F, exactly three iterations from the
// previous step's rotation. Its limit is energy-exact's rotation (the rotation factor of S).
#include <limits>

#include "own_method.hpp"
#include "rotation/energy_rotation.hpp"
#include "rotation/mueller2016.hpp"
#include "rotation/rotation_extractor.hpp"

namespace own {

constexpr int kIterations = 3;

class EnergyMueller : public corofem::RotationExtractor {
 public:
  EnergyMueller(const corofem::TetMesh& mesh, const corofem::Parameters&)
      : RotationExtractor(corofem::rotation_method_named(kEnergyMueller)),
        mesh_(mesh),
        rest_(corofem::rest_moment_arms(mesh)) {}

  void extract(const std::vector<corofem::Vec3>& positions,
               std::vector<corofem::Mat3>& rotations) override {
    stats_.iterations.assign(mesh_.tets.size(), 0);
    for (int e = 0; e < mesh_.num_tets(); ++e) {
      double a = 0;
      const corofem::Mat3 s = corofem::deformed_moment(rest_[e], mesh_.tets[e], positions, a);
      int iterations = 0;
      // Stops early only where the rotation no longer moves (a zero step has no axis).
      rotations[e] = corofem::mueller2016_rotation(s, rotations[e], kIterations,
                                                   std::numeric_limits<double>::min(), iterations);
      stats_.iterations[e] = static_cast<std::uint8_t>(iterations);
    }
  }

 private:
  const corofem::TetMesh& mesh_;
  std::vector<corofem::MomentArms> rest_;
};

void register_energy_mueller() {
  corofem::register_rotation_method({.name = kEnergyMueller,
                                     .make = corofem::extractor_maker<EnergyMueller>(),
                                     .tangent = corofem::TangentFamily::MomentFactor,
                                     // In the smoke report's speed-accuracy chart too, which this
                                     // example's tests run.
                                     .in_smoke = true});
}

}  // namespace own
