// The example's methods against corofem's oracles: the rotation against the exact minimizer of
// the same energy (energy-exact), the smoother's MG-PCG against CHOLMOD's direct solve.
#include <Eigen/Geometry>
#include <iostream>

#include "mesh/box_mesh.hpp"
#include "own_method.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/scene_simulation.hpp"

namespace own {
namespace {

/// Warm-started, three iterations a call, the method reaches the minimizer: after 100 calls on
/// the same positions it is the exact rotation to round-off (1e-10 rad leaves room for it).
/// Mueller's iteration converges linearly: after 12 calls it was 1e-4 rad off here.
bool rotation_reaches_the_minimizer() {
  const corofem::TetMesh mesh = corofem::make_box_mesh({1, 0.6, 0.4}, {3, 2, 2});
  const corofem::Mat3 turn =
      Eigen::AngleAxisd(0.9, corofem::Vec3(1, 2, 0.5).normalized()).toRotationMatrix();
  std::vector<corofem::Vec3> moved;
  for (const corofem::Vec3& x : mesh.rest)
    moved.push_back(turn * corofem::Vec3(x.x() + 0.3 * x.y(), 0.9 * x.y(), x.z() + 0.1 * x.x()));
  std::vector<corofem::Mat3> exact(mesh.tets.size(), corofem::Mat3::Identity()), mine = exact;
  corofem::make_rotation_extractor(corofem::RotationMethod::EnergyExact, mesh)
      ->extract(moved, exact);
  auto method =
      corofem::make_rotation_extractor(corofem::rotation_method_named(kEnergyMueller), mesh);
  for (int call = 0; call < 100; ++call) method->extract(moved, mine);
  double worst = 0;
  for (std::size_t e = 0; e < mine.size(); ++e)
    worst = std::max(worst, corofem::angle_between(mine[e], exact[e]));
  std::cerr << "own_method: " << kEnergyMueller << " against energy-exact: " << worst << " rad\n";
  return worst < 1e-10;
}

nlohmann::json cube(const std::string& solver) {
  return {
      {"mesh", {{"box", {1, 1, 1}}, {"cells", {6, 6, 6}}}},
      {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
      {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 1, 1}}}}}},
      {"gravity", {0, 0, -9.81}},
      {"analysis",
       {{"type", "static"}, {"formulation", "linear"}, {"solver", solver}, {"tolerance", 1e-11}}}};
}

/// MG-PCG to 1e-11 in the residual with the smoother agrees with CHOLMOD to 1e-8.
bool smoother_solves_as_cholmod() {
  nlohmann::json scene = cube("mgpcg");
  scene["analysis"]["smoother"] = kDampedL1Jacobi;
  scene["analysis"]["levels"] = 2;
  corofem::SceneSimulation mine(corofem::parse_scene(scene, ".", "cube.json"));
  corofem::SceneSimulation direct(corofem::parse_scene(cube("cholmod"), ".", "cube.json"));
  const Eigen::VectorXd u = mine.run().displacement, want = direct.run().displacement;
  const double error = (u - want).norm() / want.norm();
  std::cerr << "own_method: MG-PCG with " << kDampedL1Jacobi << " against CHOLMOD: " << error
            << "\n";
  return error < 1e-8;
}

}  // namespace

int check_against_oracles() {
  const bool rotation = rotation_reaches_the_minimizer();
  const bool smoother = smoother_solves_as_cholmod();
  return rotation && smoother ? 0 : 1;
}

}  // namespace own
