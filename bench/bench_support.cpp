#include "bench_support.hpp"

#include <chrono>
#include <iostream>
#include <map>
#include <memory>

#include "fem/corotated_assembly.hpp"
#include "fem/loads.hpp"
#include "integrate/implicit_euler.hpp"
#include "linalg/linear_solver.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "mesh/locality_order.hpp"
#include "mesh/vertex_selection.hpp"
#include "rotation/rotation_extractor.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/scene_problem.hpp"

namespace corofem::bench {

double time_ms(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}
double warm_time_ms(const std::function<void()>& f) {
  f();
  f();
  return time_ms(f);
}

void evict_caches() {
  static std::vector<char> buffer(512u << 20);
  [[maybe_unused]] static volatile char sink;  // the writes must happen
  for (std::size_t i = 0; i < buffer.size(); i += 64) buffer[i] += 1;
  sink = buffer[buffer.size() / 2];
}

namespace {
std::filesystem::path g_models;

struct PaperModel {
  const char* surface;
  double size;                                         // gmsh MeshSizeMax of the models README
  std::array<int, 3> cells;                            // procedural stand-in: 6 * nx * ny * nz tets
  std::vector<std::pair<const char*, double>> coarse;  // the README's L1 and L2
};

const std::map<std::string, PaperModel> kModels = {
    {"bunny",
     {"bunny_L0.stl",
      0.045098,
      {19, 10, 10},
      {{"bunny_L1.stl", 0.09365}, {"bunny_L2.stl", 0.18579}}}},
    {"horse",
     {"horse_L0.stl",
      0.018747,
      {26, 15, 14},
      {{"horse_L1.stl", 0.038184}, {"horse_L2.stl", 0.08}}}},
    {"dragon",
     {"dragon_L0.stl",
      0.0163,
      {28, 20, 20},
      {{"dragon_L1.stl", 0.033}, {"dragon_L2.stl", 0.068826}}}},
};  // boxes: 11400, 32760, 67200 tets (paper 11241, 33689, 67309)
}  // namespace

void set_models_dir(const std::filesystem::path& dir) {
  g_models = dir;
}
const std::filesystem::path& models_dir() {
  return g_models;
}

FeProblem& paper_problem(const std::string& model) {
  static std::map<std::string, std::unique_ptr<FeProblem>> cache;
  auto& slot = cache[model];
  if (slot) return *slot;
  if (!g_models.empty())
    std::cerr << "corofem_bench: tetrahedralizing " << kModels.at(model).surface << "\n";
  TetMesh mesh = load_scene_mesh(paper_mesh_spec(model));
  if (!g_models.empty())
    sort_for_locality(mesh);  // as the report's scenes (gmsh's order is not local)
  std::vector<Material> materials(mesh.tets.size(), Material{1e5, 0.3, 1000});
  slot = std::make_unique<FeProblem>(make_fe_problem(std::move(mesh), std::move(materials)));
  return *slot;
}

int paper_levels(const std::string& model) {
  return model == "bunny" ? 3 : 4;
}

MeshSpec paper_mesh_spec(const std::string& model) {
  const PaperModel& paper = kModels.at(model);
  MeshSpec spec;
  if (g_models.empty()) {
    const auto& c = paper.cells;
    spec.kind = MeshSpec::Kind::Box;
    spec.box = Vec3(c[0], c[1], c[2]) * 0.05;
    spec.cells = c;
    return spec;
  }
  spec.kind = MeshSpec::Kind::Surface;
  spec.path = g_models / paper.surface;
  spec.size = paper.size;
  for (const auto& [surface, size] : paper.coarse) {
    MeshSpec level = spec;
    level.path = g_models / surface;
    level.size = size;
    spec.levels.push_back(level);
  }
  return spec;
}

int hierarchy_levels(const std::string& model, HierarchyKind kind) {
  return kind == HierarchyKind::Meshes && !g_models.empty() ? 3 : paper_levels(model);
}

BuiltHierarchy paper_transfers(const std::string& model, HierarchyKind kind, bool bare_surface) {
  const FeProblem& p = paper_problem(model);
  HierarchyParams params;
  params.kind = kind;
  params.levels = hierarchy_levels(model, kind);
  MeshSpec spec = paper_mesh_spec(model);
  if (bare_surface) spec.levels.clear();
  const std::vector<TetMesh> coarse =
      kind == HierarchyKind::Meshes
          ? coarse_meshes(spec, params.levels, model, p.mesh.num_vertices())
          : std::vector<TetMesh>{};
  return build_hierarchy(p.mesh, paper_system(model).fixed, params, coarse);
}

const PaperSystem& paper_system(const std::string& model) {
  static std::map<std::string, PaperSystem> cache;
  if (auto it = cache.find(model); it != cache.end()) return it->second;
  FeProblem& p = paper_problem(model);
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
  std::vector<Mat3> rotations(p.mesh.tets.size(), Mat3::Identity());
  polar->extract(p.positions(bent_displacement(p)), rotations);
  Eigen::VectorXd force;
  assemble_corotated(p.elements, p.mesh, p.assembly, rotations, Eigen::VectorXd::Zero(p.num_dofs()),
                     p.stiffness, force);
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
  for (int v :
       vertices_in_box(p.mesh.rest, {box[0], Vec3(box[0].x() + reach, box[1].y(), box[1].z())}))
    p.dirichlet.fix_vertex(v);
  p.external_force = gravity_load(p.mesh, p.materials, Vec3(0, 0, -9.81));
  auto polar = make_rotation_extractor(RotationMethod::Polar, p.mesh);
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
    const double s = x.x() / extent.x();  // 0..1 along the long axis
    const Eigen::AngleAxisd bend(0.8 * s, Vec3::UnitY()), twist(1.2 * s, Vec3::UnitX());
    u.segment<3>(3 * v) = (twist * bend * x) * (1 + 0.1 * s) - x;
  }
  return u;
}

}  // namespace corofem::bench
