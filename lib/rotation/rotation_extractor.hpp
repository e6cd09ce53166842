#pragma once
// Per-element rotation extraction: one interface, every method (PAPER_NOTES section 2).
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/parameters.hpp"
#include "element/element_rest.hpp"
#include "rotation/rotation_method.hpp"

namespace corofem {

/// What the last extract() did, per element.
struct ExtractionStats {
  std::vector<std::uint8_t> iterations;  ///< iterations per element (0 for closed-form methods)
  int fallbacks = 0;  ///< elements handed to a fallback (singular Newton Hessian, singular F)
  /// Elements with det F <= 0 at the last extract's positions, where the method counts them on
  /// its way (the energy methods: S = F C with C symmetric positive definite, so det S has the
  /// sign of det F); -1 where it does not (count_inverted does it then, in a pass of its own).
  int inverted = -1;
};

class RotationExtractor {
 public:
  explicit RotationExtractor(RotationMethod method) : method_(method) {}
  virtual ~RotationExtractor() = default;
  RotationMethod method() const { return method_; }
  /// The method's scene name.
  const std::string& name() const { return method_.name(); }
  /// Rotations Qhat_e taking each rest element to its deformed shape at `positions`.
  /// On entry `rotations` holds the previous step's values (warm start; identity at first).
  virtual void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) = 0;
  const ExtractionStats& stats() const { return stats_; }

 protected:
  ExtractionStats stats_;

 private:
  RotationMethod method_;
};

/// Builds the extractor of `method` for `mesh` (rest data precomputed once; the mesh must outlive
/// it) with `params` (its declared settings that `params` lacks at their defaults, others
/// ignored): the method's registered make.
std::unique_ptr<RotationExtractor> make_rotation_extractor(RotationMethod method,
                                                           const TetMesh& mesh,
                                                           const Parameters& params = {});

/// A traits record's make for an extractor built from (mesh, params) or from (mesh) alone.
template <class Extractor>
auto extractor_maker() {
  return [](const TetMesh& mesh, const Parameters& params) -> std::unique_ptr<RotationExtractor> {
    if constexpr (std::is_constructible_v<Extractor, const TetMesh&, const Parameters&>)
      return std::make_unique<Extractor>(mesh, params);
    else
      return std::make_unique<Extractor>(mesh);
  };
}

}  // namespace corofem
