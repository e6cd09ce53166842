// Loads and prescribed motions over time: ramps reach full strength when they say, prescribed
// vertices follow the rigid motion exactly, released vertices move freely, and bad timing keys
// are named.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>

#include "core/errors.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {
namespace {

nlohmann::json twisted_bar(int ramp, int release) {
  nlohmann::json move = {
      {"box", {{1 - 1e-9, 0, 0}, {1, 0.2, 0.2}}},
      {"rotate", {{"axis", {1, 0, 0}}, {"center", {1, 0.1, 0.1}}, {"degrees", 90}}},
      {"translate", {0.1, 0, 0}},
      {"ramp_steps", ramp}};
  if (release > 0) move["release_step"] = release;
  return {{"mesh", {{"box", {1, 0.2, 0.2}}, {"cells", {10, 2, 2}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 0.2, 0.2}}}}}},
          {"moves", {move}},
          {"analysis",
           {{"type", "dynamic"},
            {"solver", "cholmod"},
            {"rotation", "energy-newton"},
            {"steps", 6},
            {"dt", 0.01}}}};
}

TEST(LoadSchedule, PrescribedVerticesFollowTheRampedRigidMotionExactly) {
  SceneSimulation sim(parse_scene(twisted_bar(4, 0), ".", "twist"));
  int checked = 0;
  sim.run([&](const StepState& s) {
    const double f = std::min(1.0, s.step / 4.0);
    const Mat3 r = Eigen::AngleAxisd(f * std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix();
    for (int v = 0; v < sim.problem().mesh.num_vertices(); ++v) {
      const Vec3 x = sim.problem().mesh.rest[v];
      if (x.x() < 1 - 1e-9) continue;
      const Vec3 expected = f * Vec3(0.1, 0, 0) + (r - Mat3::Identity()) * (x - Vec3(1, 0.1, 0.1));
      // The velocity solve hits the prescribed value up to rounding (|u| ~ 0.1).
      EXPECT_LT((s.displacement.segment<3>(3 * v) - expected).norm(), 1e-12) << "step " << s.step;
      ++checked;
    }
  });
  EXPECT_EQ(checked, 6 * 9);  // 3 x 3 vertices on the end face, 6 steps
}

TEST(LoadSchedule, ReleasedVerticesMoveFreely) {
  // Released after step 4: the end face springs back towards rest, so by step 6 it has left the
  // prescribed pose (which would keep it 0.1 m to the right).
  SceneSimulation sim(parse_scene(twisted_bar(3, 5), ".", "release"));
  double end_x = 0;
  sim.run([&](const StepState& s) {
    if (s.step == 4) {
      EXPECT_NEAR(s.displacement[3 * (sim.problem().mesh.num_vertices() - 1)], 0.1, 1e-12);
    }
    if (s.step == 6) end_x = s.displacement[3 * (sim.problem().mesh.num_vertices() - 1)];
  });
  EXPECT_LT(end_x, 0.1 - 1e-4);
}

TEST(LoadSchedule, ForceRampReachesFullStrengthAtRampSteps) {
  LoadTiming t{4, 0};
  EXPECT_DOUBLE_EQ(t.factor(1), 0.25);
  EXPECT_DOUBLE_EQ(t.factor(4), 1.0);
  EXPECT_DOUBLE_EQ(t.factor(9), 1.0);
  LoadTiming released{2, 5};
  EXPECT_DOUBLE_EQ(released.factor(4), 1.0);
  EXPECT_DOUBLE_EQ(released.factor(5), 0.0);
}

TEST(LoadSchedule, BadTimingAndMovesAreNamed) {
  auto scene = twisted_bar(4, 3);  // release before the ramp ends
  try {
    parse_scene(scene, ".", "bad.json");
    FAIL() << "accepted release_step <= ramp_steps";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("moves[0].release_step"), std::string::npos) << e.what();
  }
  scene = twisted_bar(4, 0);
  scene["analysis"]["type"] = "static";
  EXPECT_THROW(parse_scene(scene, ".", "static.json"), InputError);
  scene = twisted_bar(4, 0);
  scene["moves"][0]["box"] = {{5, 5, 5}, {6, 6, 6}};
  try {
    SceneSimulation sim(parse_scene(scene, ".", "empty.json"));
    FAIL() << "accepted a move selecting no vertex";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("moves[0].box selects no vertex"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace corofem
