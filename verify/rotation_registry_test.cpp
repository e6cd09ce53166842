// The rotation registry: the built-ins in their fixed places, each made by its own traits, and a
// method registered from outside lib/ reaching the scene parser, the extractor factory, the
// tangent, `tune` and the stability study without a change elsewhere. Registration changes the
// process for good, so the user's method is registered in a child process (a death test's fork)
// and the rest of the suite never sees it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "fem/rotation_tangent.hpp"
#include "mesh/box_mesh.hpp"
#include "report/scene_catalogue.hpp"
#include "report/stability_study.hpp"
#include "rotation/polar_decomposition.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"
#include "tune/tune_axes.hpp"

namespace corofem {
namespace {

using nlohmann::json;

TEST(RotationRegistry, BuiltInsKeepTheirPlacesAndMakeThemselves) {
  const std::vector<std::string> expected = {
      "energy-newton",  "energy-exact", "polar",       "polar-fixed",
      "polar-smoothed", "qr",           "mueller2016", "none"};
  ASSERT_GE(rotation_method_names().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_EQ(rotation_method_names()[k], expected[k]);
  EXPECT_EQ(rotation_method_named("polar-fixed"), RotationMethod::PolarFixed);
  EXPECT_EQ(RotationMethod::Qr.name(), "qr");
  const TetMesh mesh = make_box_mesh({1, 1, 1}, {1, 1, 1});
  for (RotationMethod method : rotation_methods())
    EXPECT_EQ(make_rotation_extractor(method, mesh)->method(), method) << method.name();
  // Only the linear formulation stays out of the comparisons.
  for (RotationMethod method : rotation_methods())
    EXPECT_EQ(method.traits().compared, method != RotationMethod::None) << method.name();
  try {
    rotation_method_named("polar-smooth");
    ADD_FAILURE() << "an unknown name was accepted";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("polar-smoothed"), std::string::npos) << e.what();
  }
}

/// A user's method: polar decomposition turned by 0.01 rad about z, so that its rotations differ
/// from every built-in's and the test can tell whose extractor ran.
class TurnedPolar : public RotationExtractor {
 public:
  TurnedPolar(const TetMesh& mesh, RotationMethod self) : RotationExtractor(self), polar_(mesh) {}
  void extract(const std::vector<Vec3>& positions, std::vector<Mat3>& rotations) override {
    polar_.extract(positions, rotations);
    for (Mat3& q : rotations) q = q * turn();
    stats_.iterations.assign(rotations.size(), 0);
  }
  static Mat3 turn() { return Eigen::AngleAxisd(0.01, Vec3::UnitZ()).toRotationMatrix(); }

 private:
  PolarExtractor polar_;
};

/// Registers "turned-polar" and checks every place that reads the registry; gtest's failures in
/// this (child) process make its exit code 1.
void register_and_use_a_method_of_ones_own() {
  const RotationMethod turned = register_rotation_method(
      {.name = "turned-polar",
       .make = [](const TetMesh& mesh, const Parameters&) -> std::unique_ptr<RotationExtractor> {
         return std::make_unique<TurnedPolar>(mesh, rotation_method_named("turned-polar"));
       },
       .tangent = TangentFamily::PolarOfF,
       .tangent_exact = false,
       .halo_rings = [](const Parameters&) { return 2; },
       .looser = {{"mueller_iterations", {4}}}});
  EXPECT_EQ(rotation_method_named("turned-polar"), turned);
  EXPECT_THROW(register_rotation_method({.name = "turned-polar", .make = turned.traits().make}),
               std::invalid_argument);
  EXPECT_THROW(register_rotation_method({.name = "no-make"}), std::invalid_argument);

  // The factory builds the user's extractor: polar's rotations (the oracle), turned.
  TetMesh mesh = make_box_mesh({1, 0.5, 0.5}, {2, 1, 1});
  std::vector<Vec3> sheared;
  for (const Vec3& x : mesh.rest) sheared.push_back(Vec3(x.x() + 0.3 * x.y(), x.y(), x.z()));
  std::vector<Mat3> mine(mesh.tets.size(), Mat3::Identity()), polar = mine;
  make_rotation_extractor(turned, mesh)->extract(sheared, mine);
  PolarExtractor(mesh).extract(sheared, polar);
  for (std::size_t e = 0; e < mine.size(); ++e)
    EXPECT_LT((mine[e] - polar[e] * TurnedPolar::turn()).norm(), 1e-14) << "element " << e;
  // A make that builds another method's extractor is refused.
  const RotationMethod liar =
      register_rotation_method({.name = "liar", .make = RotationMethod::Polar.traits().make});
  EXPECT_THROW(make_rotation_extractor(liar, mesh), std::logic_error);

  // Scenes name it; an unknown name lists it among the allowed.
  test::TempDir dir;
  json raw = {{"mesh", {{"box", {1, 0.2, 0.2}}, {"cells", {4, 1, 1}}}},
              {"material", {{"young", 1e6}, {"poisson", 0.3}, {"density", 1000}}},
              {"fixed", {{{"box", {{0, 0, 0}, {0, 0.2, 0.2}}}}}},
              {"gravity", {0, 0, -9.81}},
              {"analysis",
               {{"type", "dynamic"},
                {"formulation", "corotational"},
                {"rotation", "turned-polar"},
                {"solver", "cholmod"},
                {"steps", 2}}}};
  const Scene scene = parse_scene(raw, dir.path(), "turned.json");
  EXPECT_EQ(scene.analysis.rotation, turned);
  json unknown = raw;
  unknown["analysis"]["rotation"] = "turned";
  try {
    parse_scene(unknown, dir.path(), "turned.json");
    ADD_FAILURE() << "an unknown method was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("turned-polar"), std::string::npos) << e.what();
  }

  // Its traits reach the tangent and the force's potential.
  EXPECT_FALSE(force_has_potential(turned));

  // `tune` tries it, and the looser setting it declared, each a scene that parses.
  std::string note;
  int seen = 0;
  for (const TuneAxis& axis : tune_axes(scene, raw, {.resolution_free = false}, note)) {
    if (axis.name != "rotation") continue;
    for (const AxisValue& v : axis.values) {
      if (v.family != "turned-polar") continue;
      ++seen;
      json patched = raw;
      patched.merge_patch(v.patch);
      EXPECT_EQ(parse_scene(patched, dir.path(), "turned.json").analysis.rotation, turned);
    }
    EXPECT_EQ(axis.values[static_cast<std::size_t>(axis.reference)].label, "energy-exact");
  }
  EXPECT_EQ(seen, 2);  // the method, and mueller_iterations=4

  // The stability study runs it on one of its scenes and records it by name.
  const json study_scene = stability_scene("bar-twist", SceneSize::Small, 2, 2);
  const json run = run_stability_case(study_scene, "bar-twist", {turned}, 2, 2);
  EXPECT_EQ(run["method"], "turned-polar");
  EXPECT_TRUE(run["completed"].get<bool>()) << run.dump();

  std::exit(::testing::Test::HasFailure() ? 1 : 0);
}

TEST(RotationRegistryDeathTest, AMethodOfOnesOwnIsParsedMadeTunedAndStudied) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(register_and_use_a_method_of_ones_own(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace corofem
