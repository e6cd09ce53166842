#pragma once
// The rotation extraction methods (PAPER_NOTES section 2) and what the rest of corofem needs to
// know of each: one traits record per method, written beside its implementation (the
// `*_traits()` function its header declares) and registered once. A user's program registers its
// own with register_rotation_method before it runs anything (lib/docs/extending.md); scenes then
// name it like a built-in, and Table 1, the speed-accuracy fronts, the model accuracy, the
// stability study and `tune` run it.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/parameters.hpp"

namespace corofem {

class RotationExtractor;
struct TetMesh;
struct RotationMethodTraits;

/// A registered rotation method: its place in the registry. The built-ins have fixed places.
class RotationMethod {
 public:
  constexpr explicit RotationMethod(int id) : id_(id) {}
  static const RotationMethod EnergyNewton;  ///< the paper's energy minimization, quaternion Newton
  static const RotationMethod EnergyExact;   ///< the closed-form minimizer of the same energy
  static const RotationMethod Polar;         ///< polar decomposition of F
  static const RotationMethod PolarFixed;    ///< SVD of F with inversion handling (Irving et al.)
  static const RotationMethod PolarSmoothed;  ///< polar, then 1-ring averaging (paper section 5)
  static const RotationMethod Qr;             ///< Gram-Schmidt frame of the edges
  static const RotationMethod Mueller2016;    ///< Mueller et al. 2016's iteration on F
  static const RotationMethod None;           ///< identity: the linear formulation

  constexpr int id() const { return id_; }
  const RotationMethodTraits& traits() const;
  /// The scene name.
  const std::string& name() const;
  friend constexpr bool operator==(RotationMethod, RotationMethod) = default;
  friend constexpr auto operator<=>(RotationMethod, RotationMethod) = default;

 private:
  int id_;
};
inline constexpr RotationMethod RotationMethod::EnergyNewton{0};
inline constexpr RotationMethod RotationMethod::EnergyExact{1};
inline constexpr RotationMethod RotationMethod::Polar{2};
inline constexpr RotationMethod RotationMethod::PolarFixed{3};
inline constexpr RotationMethod RotationMethod::PolarSmoothed{4};
inline constexpr RotationMethod RotationMethod::Qr{5};
inline constexpr RotationMethod RotationMethod::Mueller2016{6};
inline constexpr RotationMethod RotationMethod::None{7};

/// Which closed form differentiates a method's rotation (fem/rotation_tangent.hpp): the rotation
/// factor of F, of the quadrature moment S = F C (eq. 3), the Gram-Schmidt frame, the identity.
enum class TangentFamily { PolarOfF, MomentFactor, GramSchmidt, Identity };

/// A rotation parameter the tuner also tries at these looser values (the method stopped earlier).
struct LooserSetting {
  std::string param{};  ///< a key of analysis.rotation_params (one of the method's parameters)
  std::vector<double> values{};
};

struct RotationMethodTraits {
  std::string name{};  ///< the scene's analysis.rotation
  /// Builds the extractor for a mesh (which outlives it); its constructor passes this method to
  /// RotationExtractor's.
  std::function<std::unique_ptr<RotationExtractor>(const TetMesh&, const Parameters&)> make{};
  /// Its own settings (core/parameters.hpp), scene keys of analysis.rotation_params: the scene
  /// reader reads them by this declaration alone, make_rotation_extractor fills what a scene
  /// leaves at their defaults, and the record writes them.
  std::vector<ParameterSpec> parameters{};
  /// Those of its settings that are stopping tolerances: a static run tightens them to below its
  /// own tolerance (scene/scene.cpp: its residual is the user's criterion) unless the scene sets
  /// them.
  std::vector<std::string> static_tolerances{};
  TangentFamily tangent = TangentFamily::PolarOfF;
  /// Whether the family's dQ is the derivative of this method's own rotation (or of the limit it
  /// iterates to); false where it leaves out a coupling (polar-smoothed's neighbours): Newton then
  /// converges linearly.
  bool tangent_exact = true;
  /// Whether the corotated force is the gradient of elastic_energy (polar of F: the rotation's
  /// variation does no work).
  bool force_has_potential = false;
  /// Rings of neighbouring tets a rank's part must hold for this method (an averaging method: one
  /// per pass); none if unset.
  std::function<int(const Parameters&)> halo_rings{};
  /// What `tune` also tries besides the method's defaults.
  std::vector<LooserSetting> looser{};
  /// Whether the comparisons run it (speed-accuracy, model accuracy, stability, tune): all but the
  /// linear formulation.
  bool compared = true;
  /// Whether the smoke report's speed-accuracy chart runs it (two methods keep it short).
  bool in_smoke = false;
};

/// Adds a method; its name must be new. Returns its handle.
RotationMethod register_rotation_method(RotationMethodTraits traits);
/// Every registered method, built-ins first, in registration order.
std::vector<RotationMethod> rotation_methods();
std::vector<std::string> rotation_method_names();
std::optional<RotationMethod> find_rotation_method(std::string_view name);
/// The method named `name`; std::out_of_range naming the registered ones for another (tests and
/// tools: a scene's string goes through scene/'s parser, which names the key).
RotationMethod rotation_method_named(std::string_view name);

}  // namespace corofem
