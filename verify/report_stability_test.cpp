// The stability study's scenes, small: the energy methods (the paper's claim) finish without NaN
// and below the flutter thresholds. The rivals are not gated here: where they fail is a measured
// fact of the report (stability.json), not a test to pass. A run that blows up is recorded as
// diverged, with its step, and does not stop the study.
#include <gtest/gtest.h>

#include <map>
#include <sstream>

#include "core/threads.hpp"
#include "mesh/tet_mesh.hpp"
#include "report/report_config.hpp"
#include "report/stability_study.hpp"

namespace corofem {
namespace {

using nlohmann::json;

TEST(Stability, EnergyMethodsStayStableOnEverySmallScene) {
  ReportConfig quick;
  quick.mode = ReportConfig::Mode::Quick;
  const FlutterThresholds thresholds;
  for (const std::string& id : stability_scene_ids(false)) {
    const json scene =
        stability_scene(id, SceneSize::Small, quick.stability_ramp(), quick.stability_hold());
    for (const char* method : {"energy-newton", "energy-exact"}) {
      const json run = run_stability_case(scene, id, {rotation_method_named(method)},
                                          quick.stability_ramp(), quick.stability_hold());
      SCOPED_TRACE(id + " " + method);
      ASSERT_TRUE(run["completed"].get<bool>()) << run.dump();
      ASSERT_NE(run["status"], "diverged") << run.dump();
      EXPECT_TRUE(run["residual_final"].is_number());  // finite: no NaN anywhere
      // Measured, not gated: pulled 2.5x harder, the quadruped keeps moving under the energy
      // methods (kinetic energy ~400 J after the hold, against ~1 J under polar): the paper's
      // claim does not hold there, and stability.json records it. Everywhere else it holds.
      if (id == "quadruped-stretched-far") continue;
      EXPECT_EQ(run["status"], "stable")
          << "rms " << run["flutter_rms_rad"] << " max " << run["flutter_max_rad"];
      EXPECT_LT(run["flutter_max_rad"].get<double>(), thresholds.max_rad);
      EXPECT_LT(run["flutter_rms_rad"].get<double>(), thresholds.rms_rad);
    }
  }
}

/// The study runs its (scene, method) groups side by side, one thread each: the records must not
/// depend on it. The smoke study of the twisted bar (seven methods, both integrators) at one
/// thread and at three (more workers than this machine's cores: groups finish out of order) gives
/// the same runs, references and verdicts, every value to the last bit; and every progress line
/// whole.
TEST(Stability, SameStudyAtEveryThreadCount) {
  ReportConfig smoke;
  smoke.mode = ReportConfig::Mode::Smoke;
  smoke.only = "bar-twist";
  std::ostringstream lines;
  smoke.progress = &lines;
  json one, three;
  {
    const ScopedThreadCount threads(1);
    one = run_stability_study(smoke);
  }
  lines.str("");
  {
    const ScopedThreadCount threads(3);
    three = run_stability_study(smoke);
  }
  ASSERT_FALSE(one["runs"].empty());
  for (const char* key : {"runs", "references", "verdicts", "poses", "surfaces"})
    EXPECT_EQ(one[key].dump(), three[key].dump()) << key;
  std::istringstream in(lines.str());
  int count = 0;
  for (std::string line; std::getline(in, line); ++count)
    EXPECT_EQ(line.rfind("report: stability ", 0), 0u) << "a line mixed with another: " << line;
  EXPECT_GE(count, 7 * 2);  // every group's two runs at dt at least
}

TEST(Stability, BlowUpIsRecordedAsDivergedWithItsStep) {
  // A bar pulled by 1e12 N: the displacement leaves any physical range within a few steps.
  json scene = stability_scene("bar-stretch", SceneSize::Small, 2, 4);
  scene.erase("moves");
  scene["forces"] =
      json::array({{{"box", {{1 - 1e-6, 0, 0}, {1, 0.2, 0.2}}}, {"total", {1e12, 0, 0}}}});
  const json run = run_stability_case(scene, "bar-pulled-apart", {RotationMethod::Polar}, 2, 4);
  ASSERT_TRUE(run["completed"].get<bool>()) << run.dump();
  EXPECT_EQ(run["status"], "diverged");
  ASSERT_TRUE(run["diverged_step"].is_number_integer());
  EXPECT_GE(run["diverged_step"].get<int>(), 1);
  EXPECT_LE(run["diverged_step"].get<int>(), 6);
  EXPECT_EQ(run["divergence"]["kind"], "numerical");
}

TEST(Stability, ABodyLeftInsideOutIsStuckNotStable) {
  // block-squash at the quick report's ramp and hold (40, 100 steps): the cube's top pushed through
  // its base and released. Polar cannot tell an inverted element from a turned one and leaves the
  // body crumpled (the paper's Figures 4-5): a third of the elements still inverted at the end,
  // with no flutter, counted as stable before issue 40. The energy method recovers: none left.
  const json scene = stability_scene("block-squash", SceneSize::Small, 40, 100);
  const json polar = run_stability_case(scene, "block-squash", {RotationMethod::Polar}, 40, 100);
  ASSERT_TRUE(polar["completed"].get<bool>()) << polar.dump();
  EXPECT_EQ(polar["status"], "stuck") << polar["inverted_final"];
  EXPECT_GT(polar["inverted_final"].get<int>(),
            FlutterThresholds{}.stuck_inverted_share * polar["tets"].get<int>());
  const json energy =
      run_stability_case(scene, "block-squash", {RotationMethod::EnergyNewton}, 40, 100);
  ASSERT_TRUE(energy["completed"].get<bool>()) << energy.dump();
  EXPECT_EQ(energy["inverted_final"], 0);
  EXPECT_NE(energy["status"], "stuck");
}

TEST(Stability, RunsRecordIntegratorStepEnergyAndAsymmetry) {
  // bar-twist, small: polar is conservative (asymmetry at rounding level) and, under Newton,
  // creates no energy; energy-exact's element Jacobians are measurably asymmetric.
  // 450 degrees over 30 steps (15 per step; the smoke report's 75 per step makes every method
  // flutter).
  const json scene = stability_scene("bar-twist", SceneSize::Small, 30, 6);
  const json polar =
      run_stability_case(scene, "bar-twist", {RotationMethod::Polar, Integrator::Newton, 2}, 30, 6);
  ASSERT_TRUE(polar["completed"].get<bool>()) << polar.dump();
  EXPECT_EQ(polar["integrator"], "newton");
  EXPECT_DOUBLE_EQ(polar["dt"].get<double>(), 0.005);
  EXPECT_EQ(polar["steps_run"], 72);  // (30 + 6) x 2
  EXPECT_LT(polar["asymmetry"].get<double>(), 1e-12);
  EXPECT_LT(polar["energy_error"].get<double>(), 1e-6);
  EXPECT_TRUE(polar["cause"].is_null());
  const json energy = run_stability_case(
      scene, "bar-twist", {RotationMethod::EnergyExact, Integrator::Newton, 1}, 30, 6);
  ASSERT_TRUE(energy["asymmetry"].is_number()) << energy["status"];
  EXPECT_GT(energy["asymmetry"].get<double>(), 1e-4);
}

json fake_run(const std::string& integrator, double dt, const std::string& status) {
  return {{"integrator", integrator},
          {"dt", dt},
          {"status", status},
          {"flutter_max_rad", status == "flutter" ? json(0.8) : json(0.001)},
          {"diverged_step", nullptr}};
}

TEST(Stability, CausesComeFromTheOtherIntegratorAndTheSmallerStep) {
  // Not stable under linear-implicit, stable under Newton: the integrator.
  std::vector<json> runs = {
      fake_run("linear-implicit", 0.01, "flutter"), fake_run("newton", 0.01, "stable"),
      fake_run("linear-implicit", 0.005, "stable"), fake_run("newton", 0.005, "stable")};
  std::vector<json*> group;
  for (json& r : runs) group.push_back(&r);
  attribute_causes(group);
  EXPECT_EQ(runs[0]["cause"], "integrator");
  EXPECT_NE(runs[0]["cause_detail"].get<std::string>().find("but newton at dt 0.01: stable"),
            std::string::npos)
      << runs[0]["cause_detail"];
  // Failing under both integrators at dt, stable under linear-implicit at dt/2: the step size, an
  // integrator matter too.
  runs = {fake_run("linear-implicit", 0.01, "flutter"), fake_run("newton", 0.01, "diverged"),
          fake_run("linear-implicit", 0.005, "stable"), fake_run("newton", 0.005, "flutter")};
  attribute_causes(group);
  EXPECT_EQ(runs[0]["cause"], "integrator");
  EXPECT_EQ(runs[1]["cause"], "integrator");
  EXPECT_EQ(runs[3]["cause"], "integrator");
  EXPECT_FALSE(runs[2].contains("cause"));
  // Failing everywhere: the method, for every run.
  runs = {fake_run("linear-implicit", 0.01, "flutter"), fake_run("newton", 0.01, "diverged"),
          fake_run("linear-implicit", 0.005, "flutter"), fake_run("newton", 0.005, "flutter")};
  attribute_causes(group);
  for (const json& r : runs) EXPECT_EQ(r["cause"], "method") << r.dump();
  // Only Newton runs that did not converge to compare with: no cause is claimed.
  runs = {fake_run("linear-implicit", 0.01, "flutter"), fake_run("newton", 0.01, "diverged"),
          fake_run("newton", 0.005, "diverged"), fake_run("newton", 0.005, "diverged")};
  for (int k = 1; k < 4; ++k) runs[k]["divergence"] = {{"kind", "not_converged"}};
  attribute_causes(group);
  EXPECT_TRUE(runs[0]["cause"].is_null());
}

json fluttering(const std::string& integrator, double dt, double rms_rad) {
  json run = fake_run(integrator, dt, "flutter");
  run["flutter_rms_rad"] = rms_rad;
  return run;
}

TEST(Stability, TheRefinedReferenceTellsMotionFromFlutter) {
  // Every run flutters at 0.02 rad a step (2 rad/s at dt 0.01, 4 at dt 0.005): nothing in the
  // group explains it, so the same method under Newton at dt/4 decides.
  const auto group_of = [](std::vector<json>& runs) {
    runs = {fluttering("linear-implicit", 0.01, 0.02), fluttering("newton", 0.01, 0.02),
            fluttering("linear-implicit", 0.005, 0.02), fluttering("newton", 0.005, 0.02)};
    std::vector<json*> group;
    for (json& r : runs) group.push_back(&r);
    return group;
  };
  std::vector<json> runs;
  std::vector<json*> group = group_of(runs);
  EXPECT_TRUE(needs_refined_reference(runs));
  // The refined run moves at 1.5 rad/s (0.00375 rad per 0.0025 s step): at least half of the
  // dt runs' 2 rad/s, so their motion is the scene's; the dt/2 runs' 4 rad/s is more than twice
  // it, numerical.
  json reference = fluttering("newton", 0.0025, 0.00375);
  reference["status"] = "stable";
  attribute_causes(group, &reference);
  EXPECT_EQ(runs[0]["cause"], "scene") << runs[0]["cause_detail"];
  EXPECT_EQ(runs[1]["cause"], "scene");
  EXPECT_EQ(runs[2]["cause"], "integrator");
  EXPECT_NE(runs[0]["cause_detail"].get<std::string>().find("refined reference newton at dt "
                                                            "0.0025: stable"),
            std::string::npos)
      << runs[0]["cause_detail"];
  // A reference that diverges or stays inverted: the method's failure.
  group = group_of(runs);
  reference["status"] = "stuck";
  reference["inverted_final"] = 40;
  attribute_causes(group, &reference);
  for (const json& r : runs) EXPECT_EQ(r["cause"], "method") << r.dump();
  // A reference whose Newton cannot solve the steps says nothing against the method.
  group = group_of(runs);
  reference["status"] = "diverged";
  reference["divergence"] = {{"kind", "not_converged"}};
  attribute_causes(group, &reference);
  for (const json& r : runs) EXPECT_EQ(r["cause"], "integrator") << r.dump();
  reference["divergence"] = {{"kind", "numerical"}};  // a blow-up does
  group = group_of(runs);
  attribute_causes(group, &reference);
  for (const json& r : runs) EXPECT_EQ(r["cause"], "method") << r.dump();
  reference.erase("divergence");
  // Motion of the scene, unless another method settles it under the same integrator and step.
  group = group_of(runs);
  reference["status"] = "flutter";
  reference["flutter_rms_rad"] = 0.01;  // 4 rad/s: the same motion as every run
  attribute_causes(group, &reference);
  json all = json::array();
  for (json r : runs) {
    EXPECT_EQ(r["cause"], "scene") << r.dump();
    r["scene"] = "s";
    r["method"] = "qr";
    all.push_back(r);
  }
  json settled = fake_run("newton", 0.01, "stable");
  settled["scene"] = "s";
  settled["method"] = "polar";
  all.push_back(settled);
  attribute_scene_causes(all, "s");
  EXPECT_EQ(all[0]["cause"], "scene");  // linear-implicit at dt: no method settles it
  EXPECT_EQ(all[0]["status"], "motion");
  EXPECT_EQ(all[1]["cause"], "method");  // newton at dt: polar settles it
  EXPECT_EQ(all[1]["status"], "flutter");
  EXPECT_NE(all[1]["cause_detail"].get<std::string>().find("polar settles the scene there"),
            std::string::npos);
  // A scene nothing settles: failures the refined reference could not judge (Newton unsolved)
  // are the scene's; a blow-up stays the method's.
  json unsettled = json::array();
  for (const char* method : {"polar", "qr"}) {
    json flutter = fluttering("linear-implicit", 0.01, 0.05),
         diverged = fake_run("newton", 0.01, "diverged");
    diverged["divergence"] = {
        {"kind", std::string(method) == "qr" ? "numerical" : "not_converged"}};
    for (json* r : {&flutter, &diverged}) {
      (*r)["scene"] = "horse";
      (*r)["method"] = method;
      (*r)["cause"] = "integrator";
      (*r)["cause_detail"] = "";
    }
    diverged["cause"] = std::string(method) == "qr" ? "method" : "integrator";
    unsettled.push_back(flutter);
    unsettled.push_back(diverged);
  }
  attribute_scene_causes(unsettled, "horse");
  EXPECT_EQ(unsettled[0]["cause"], "scene");
  EXPECT_EQ(unsettled[0]["status"], "flutter");  // not shown to be motion
  EXPECT_EQ(unsettled[1]["cause"], "scene");
  EXPECT_EQ(unsettled[2]["cause"], "scene");
  EXPECT_EQ(unsettled[3]["cause"], "method");  // qr's blow-up
}

/// A cantilever 1 x 0.1 x 0.1 m (E 1e7: its first bending mode at 1.6 Hz) with its tip lifted
/// 0.3 m over `ramp` steps, then released to swing undamped for `hold` steps.
json released_cantilever(int ramp, int hold) {
  json s;
  s["analysis"] = {{"type", "dynamic"},   {"formulation", "corotational"},
                   {"rotation", "polar"}, {"solver", "cholmod"},
                   {"dt", 0.01},          {"steps", ramp + hold},
                   {"max_iterations", 30}};
  s["mesh"] = {{"box", {1.0, 0.1, 0.1}}, {"cells", {20, 2, 2}}};
  s["material"] = {{"young", 1e7}, {"poisson", 0.3}, {"density", 1000}};
  s["fixed"] = json::array({{{"box", {{0, 0, 0}, {1e-6, 0.1, 0.1}}}}});
  s["moves"] = json::array({{{"box", {{1 - 1e-6, 0, 0}, {1, 0.1, 0.1}}},
                             {"translate", {0, 0, 0.3}},
                             {"ramp_steps", ramp},
                             {"release_step", ramp + 1}}});
  return s;
}

TEST(Stability, AReleasedCantileverSwingsAsMotionNotFlutter) {
  // Undamped, it keeps swinging through the hold: rotation changes above the flutter thresholds
  // at dt, and the same motion under Newton at dt/4. Its runs are the scene's motion.
  MethodPlan plan{20, 60};
  const MethodRuns m =
      run_method_on_scene(released_cantilever(20, 60), "released", RotationMethod::Polar, plan);
  ASSERT_FALSE(m.reference.is_null());
  json runs = m.runs;
  // Over the array's vector: a range-for over the json itself made GCC 12 warn (-Warray-bounds,
  // falsely) of the object map's begin.
  for (json& r : runs.get_ref<json::array_t&>()) r["scene"] = "released";
  attribute_scene_causes(runs, "released");
  for (const json& r : runs) {
    std::cout << r["integrator"] << " dt " << r["dt"] << ": " << r["status"] << ", "
              << r["cause_detail"] << "\n";
    if (r["status"] != "stable") {
      EXPECT_EQ(r["cause"], "scene") << r["cause_detail"];
      EXPECT_EQ(r["status"], "motion");
    }
  }
  EXPECT_NE(runs[0]["status"], "stable");  // the scene is built to move above the thresholds
}

TEST(Stability, APlantedNonConservativeForceIsStillCaught) {
  // bar-stretch at the quick report's ramp and hold: QR's frame follows one edge, so its force is
  // not a gradient (asymmetry 0.79 measured) and under the linearly implicit step it creates
  // energy (0.19 of the hold's) and flutters; polar on the same run is conservative (asymmetry
  // 4e-16), creates none and settles. Newton's robustness must not hide this.
  const json scene = stability_scene("bar-stretch", SceneSize::Small, 40, 100);
  const json qr = run_stability_case(scene, "bar-stretch", {RotationMethod::Qr}, 40, 100);
  const json polar = run_stability_case(scene, "bar-stretch", {RotationMethod::Polar}, 40, 100);
  ASSERT_TRUE(qr["completed"].get<bool>()) << qr.dump();
  ASSERT_TRUE(polar["completed"].get<bool>()) << polar.dump();
  EXPECT_EQ(qr["status"], "flutter");
  EXPECT_GT(qr["energy_error"].get<double>(), 0.05);
  EXPECT_GT(qr["asymmetry"].get<double>(), 0.1);
  EXPECT_EQ(polar["status"], "stable");
  EXPECT_LT(polar["energy_error"].get<double>(), 1e-6);
  EXPECT_LT(polar["asymmetry"].get<double>(), 1e-12);
}

TEST(Stability, PoseIsTheClosedOutwardBoundarySurface) {
  // The bar, 1 x 0.2 x 0.2 m in 20 x 4 x 4 cells: its boundary has 21 x 5 x 5 - 19 x 3 x 3 = 354
  // vertices; a closed surface has every edge in two triangles, once in each direction, and by
  // the divergence theorem encloses sum over triangles of x . n / 3 = the box's 0.04 m^3
  // (positive only if every normal points out). Coordinates are stored to 1e-4 m, exact here.
  const json scene = stability_scene("bar-twist", SceneSize::Small, 2, 2);
  json pose;
  const json run = run_stability_case(scene, "bar-twist", {RotationMethod::Polar}, 2, 2, &pose);
  ASSERT_TRUE(run["completed"].get<bool>()) << run.dump();
  ASSERT_FALSE(pose.is_null());
  EXPECT_EQ(pose["status"], run["status"]);
  const json& rest = pose["rest_points"];
  ASSERT_EQ(rest.size(), 354u);
  ASSERT_EQ(pose["points"].size(), rest.size());
  ASSERT_EQ(pose["rotation_change_max_rad"].size(), rest.size());
  std::map<std::pair<int, int>, int> directed;
  double volume = 0;
  for (const json& t : pose["triangles"]) {
    const int v[3] = {t[0].get<int>(), t[1].get<int>(), t[2].get<int>()};
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(v[k], 0);
      ASSERT_LT(v[k], static_cast<int>(rest.size()));
      ++directed[{v[k], v[(k + 1) % 3]}];
    }
    const auto p = [&](int k) { return Vec3(rest[v[k]][0], rest[v[k]][1], rest[v[k]][2]); };
    volume += p(0).dot(p(1).cross(p(2))) / 6;
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << edge.first << "->" << edge.second;
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u)
        << edge.first << "-" << edge.second << " is open";
  }
  EXPECT_NEAR(volume, 0.04, 1e-12);
}

}  // namespace
}  // namespace corofem
