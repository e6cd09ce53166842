// corofem_profile: a driver for cache profilers. Builds a paper model's hierarchy, then runs N
// Galerkin updates of one method, or N whole time steps (METHOD "step": energy-newton rotations,
// assembly, stream update, MG-PCG to 1e-4; the body fixed at its x-min face under gravity).
// N = 0 measures the setup alone, so a profiler's difference of two runs isolates the work.
// Usage: corofem_profile METHOD MODEL N [--models DIR]
#include <cstring>
#include <iostream>
#include <optional>
#include <string>

#include "bench_support.hpp"
#include "core/errors.hpp"
#include "fem/loads.hpp"
#include "integrate/implicit_euler.hpp"
#include "multigrid/hierarchy.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "rotation/rotation_extractor.hpp"

int main(int argc, char** argv) {
  using namespace corofem;
  if (argc < 4) {
    std::cerr << "usage: corofem_profile naive|stream|stream-full|reuse|gather|step "
                 "bunny|horse|dragon N [--models DIR]\n";
    return 2;
  }
  if (argc == 6 && std::strcmp(argv[4], "--models") == 0) bench::set_models_dir(argv[5]);
  try {
    const std::string method = argv[1], model = argv[2];
    const int updates = std::stoi(argv[3]);
    const FeProblem& p = bench::paper_problem(model);
    const auto& system = bench::paper_system(model);
    if (method == "step") {
      FeProblem problem = p;  // a copy with this run's supports and loads
      for (int v = 0; v < problem.mesh.num_vertices(); ++v)
        if (system.fixed[v]) problem.dirichlet.fix_vertex(v);
      problem.external_force = gravity_load(problem.mesh, problem.materials, Vec3(0, 0, -9.81));
      auto rotations = make_rotation_extractor(RotationMethod::EnergyNewton, problem.mesh);
      MultigridParams params;
      params.hierarchy.kind = HierarchyKind::Meshes;
      params.hierarchy.levels = bench::hierarchy_levels(model, HierarchyKind::Meshes);
      params.tolerance = 1e-4;
      MultigridSolver solver(problem.stiffness,
                             bench::paper_transfers(model, HierarchyKind::Meshes), params, true);
      DynamicOptions options;
      options.steps = updates;
      solve_dynamic(problem, *rotations, solver, options);
      std::cout << "fine_blocks " << system.matrix.num_blocks() << "\ntets " << p.mesh.num_tets()
                << "\n";
      return 0;
    }
    MultigridHierarchy h(system.matrix,
                         bench::paper_transfers(model, HierarchyKind::Meshes).transfers);
    const std::optional<GalerkinMethod> found = kGalerkinMethods.find(method);
    if (!found) {
      std::cerr << "galerkin_profile: unknown method '" << method << "'\n";
      return 2;
    }
    const GalerkinMethod m = *found;
    h.prepare(m);  // the method's streams, built before the profiled updates
    for (int i = 0; i < updates; ++i) h.update(system.matrix, m);
    // Machine-readable facts for the script: blocks of K and of all levels.
    std::size_t blocks = 0;
    for (int l = 0; l < h.num_levels(); ++l) blocks += h.matrix(l).num_blocks();
    std::cout << "fine_blocks " << system.matrix.num_blocks() << "\nall_blocks " << blocks
              << "\ntets " << p.mesh.num_tets() << "\nchecksum " << h.matrix(1).values[0] << "\n";
  } catch (const std::exception& e) {
    std::cerr << "corofem_profile: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
