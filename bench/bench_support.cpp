#include "bench_support.hpp"

#include <iostream>
#include <map>
#include <memory>

#include "fem/corotated_assembly.hpp"
#include "fem/implicit_euler.hpp"
#include "fem/loads.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/vertex_selection.hpp"
#include "rotation/rotation_extractor.hpp"
#include "solver/linear_solver.hpp"
#include "mesh/gmsh_mesh.hpp"

namespace corofem::bench {
namespace {
std::filesystem::path g_models;

struct PaperModel {
  const char* surface;
  double size;                // gmsh MeshSizeMax of the models README
  std::array<int, 3> cells;   // procedural stand-in: 6 * nx * ny * nz tets
};

const std::map<std::string, PaperModel> kModels = {
    {"bunny", {"bunny_L0.stl", 0.045098, {19, 10, 10}}},   // 11400 tets (paper 11241)
    {"horse", {"horse_L0.stl", 0.018747, {26, 15, 14}}},   // 32760 tets (paper 33689)
    {"dragon", {"dragon_L0.stl", 0.0163, {28, 20, 20}}},   // 67200 tets (paper 67309)
};
}  // namespace

void set_models_dir(const std::filesystem::path& dir) { g_models = dir; }
const std::filesystem::path& models_dir() { return g_models; }

FeProblem& paper_problem(const std::string& model) {
  static std::map<std::string, std::unique_ptr<FeProblem>> cache;
  auto& slot = cache[model];
  if (slot) return *slot;
  const PaperModel& spec = kModels.at(model);
  TetMesh mesh;
  if (!g_models.empty()) {
    std::cerr << "corofem_bench: tetrahedralizing " << spec.surface << "\n";
    mesh = tetrahedralize_surface(g_models / spec.surface, spec.size);
  } else {
    const auto& c = spec.cells;
    mesh = make_box_mesh(Vec3(c[0], c[1], c[2]) * 0.05, c);
  }
  std::vector<Material> materials(mesh.tets.size(), Material{1e5, 0.3, 1000});
  slot = std::make_unique<FeProblem>(make_fe_problem(std::move(mesh), std::move(materials)));
  return *slot;
}

int paper_levels(const std::string& model) { return model == "bunny" ? 3 : 4; }

const PaperSystem& paper_system(const std::string& model) {
  static std::map<std::string, PaperSystem> cache;
  if (auto it = cache.find(model); it != cache.end()) return it->second;
  FeProblem& p = paper_problem(model);
  auto polar = make_rotation_extractor("polar", p.mesh);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  polar->extract(p.positions(bent_displacement(p)), rotations);
  Eigen::VectorXd f0;
  assemble_corotated(p.elements, p.mesh.tets, p.assembly, rotations, p.stiffness, f0);
  DirichletConditions bc = DirichletConditions::none(p.num_dofs());
  const auto box = bounding_box(p.mesh.rest);
  PaperSystem s{p.stiffness, gravity_load(p.mesh, p.materials, Vec3(0, 0, -9.81)),
                std::vector<char>(p.mesh.rest.size(), 0)};
  for (int v = 0; v < p.mesh.num_vertices(); ++v)
    if (p.mesh.rest[v].x() < box[0].x() + 1e-9) {
      bc.fix_vertex(v);
      s.fixed[v] = 1;
    }
  apply_dirichlet(bc, s.matrix, s.rhs);
  return cache[model] = std::move(s);
}

const SimulatedFrames& simulated_frames(const std::string& model) {
  static std::map<std::string, SimulatedFrames> cache;
  if (auto it = cache.find(model); it != cache.end()) return it->second;
  FeProblem p = paper_problem(model);  // a copy: loads and supports are this simulation's own
  const auto box = bounding_box(p.mesh.rest);
  const double reach = 0.02 * (box[1] - box[0]).x();
  for (int v : vertices_in_box(p.mesh.rest, {box[0], Vec3(box[0].x() + reach, box[1].y(), box[1].z())}))
    p.dirichlet.fix_vertex(v);
  p.external_force = gravity_load(p.mesh, p.materials, Vec3(0, 0, -9.81));
  auto polar = make_rotation_extractor("polar", p.mesh);
  auto solver = make_cholmod_solver();
  SimulatedFrames frames;
  std::cerr << "corofem_bench: simulating 8 steps of " << model << " for rotation frames\n";
  solve_dynamic(p, *polar, *solver, {true, 0.01, 8, 0, 0}, [&](const StepState& s) {
    if (s.step == 7) frames.previous = s.displacement;
    if (s.step == 8) frames.current = s.displacement;
  });
  return cache[model] = std::move(frames);
}

Eigen::VectorXd bent_displacement(const FeProblem& problem) {
  const auto box = bounding_box(problem.mesh.rest);
  const Vec3 extent = box[1] - box[0];
  Eigen::VectorXd u(problem.num_dofs());
  for (int v = 0; v < problem.mesh.num_vertices(); ++v) {
    const Vec3 x = problem.mesh.rest[v] - box[0];
    const double s = x.x() / extent.x();                        // 0..1 along the long axis
    const Eigen::AngleAxisd bend(0.8 * s, Vec3::UnitY()), twist(1.2 * s, Vec3::UnitX());
    u.segment<3>(3 * v) = (twist * bend * x) * (1 + 0.1 * s) - x;
  }
  return u;
}

}  // namespace corofem::bench
