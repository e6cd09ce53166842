#pragma once
// Per-element rotation extraction: one interface, many methods (PAPER_NOTES section 2).
#include <memory>
#include <string>
#include <vector>

#include "fem/element_rest.hpp"

namespace corofem {

class RotationExtractor {
 public:
  virtual ~RotationExtractor() = default;
  virtual std::string name() const = 0;
  /// Rotations Qhat_e taking each rest element to its deformed shape at `positions`.
  /// On entry `rotations` holds the previous step's values (warm start; identity at first).
  virtual void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) = 0;
};

/// Scene names of the available extractors.
std::vector<std::string> rotation_method_names();

/// Builds the named extractor for `mesh` (rest data precomputed once). Throws InputError naming
/// `analysis.rotation` for an unknown name.
std::unique_ptr<RotationExtractor> make_rotation_extractor(const std::string& name,
                                                           const TetMesh& mesh);

}  // namespace corofem
