#include "cli/export_matrices.hpp"

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "integrate/implicit_euler.hpp"
#include "integrate/static_solver.hpp"
#include "io/matrix_market.hpp"
#include "io/run_context.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

namespace {
/// "A3.mtx" and the like (built with append: GCC 12 warns falsely on "A" + std::to_string(l)).
std::string level_file(char prefix, int level) {
  std::string name(1, prefix);
  name.append(std::to_string(level)).append(".mtx");
  return name;
}
}  // namespace

void export_matrices(const Scene& scene, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError("cannot create output folder '" + dir.string() + "'");
  check_writable(dir / "levels.json");
  FeProblem problem = build_problem(scene);
  AnalysisSpec a = scene.analysis;
  const bool corotational = a.formulation == Formulation::Corotational;
  auto extractor = make_rotation_extractor(corotational ? a.rotation : RotationMethod::None,
                                           problem.mesh, a.rotation_params);
  auto multigrid =
      make_multigrid_solver(a, problem, coarse_meshes(scene, problem.mesh.num_vertices()), false);
  MultigridSolver& solver = *multigrid;
  if (a.type == AnalysisType::Static) {
    solve_static(problem, *extractor, solver, {corotational, a.load_steps, a.tolerance, 1});
  } else {
    solve_dynamic(problem, *extractor, solver,
                  {corotational, a.dt, 1, a.rayleigh_alpha, a.rayleigh_beta});
  }
  const MultigridHierarchy& h = solver.hierarchy();
  nlohmann::json levels = nlohmann::json::array();
  for (int l = 0; l < h.num_levels(); ++l) {
    const auto m = to_eigen(h.matrix(l));
    write_matrix_market(dir / level_file('A', l), m);
    nlohmann::json level = {{"level", l},
                            {"vertices", h.matrix(l).block_rows},
                            {"dofs", m.rows()},
                            {"nonzeros", m.nonZeros()},
                            {"file", level_file('A', l)}};
    if (l + 1 < h.num_levels()) {
      const auto r = restriction_matrix(h.transfer(l));
      write_matrix_market(dir / level_file('R', l), r);
      level["restriction"] = {{"file", level_file('R', l)},
                              {"rows", r.rows()},
                              {"cols", r.cols()},
                              {"nonzeros", r.nonZeros()}};
    }
    levels.push_back(level);
  }
  // The fine vertices' rest positions (n x 3, every entry stored): what a rival's rigid-body modes
  // (PETSc's MatNullSpaceCreateRigidBody, PyAMG's) and bench/multigrid_diagnosis.py need.
  const std::vector<Vec3>& rest = problem.mesh.rest;
  std::vector<Eigen::Triplet<double>> xyz;
  xyz.reserve(3 * rest.size());
  for (std::size_t v = 0; v < rest.size(); ++v)
    for (int c = 0; c < 3; ++c) xyz.emplace_back(static_cast<int>(v), c, rest[v][c]);
  Eigen::SparseMatrix<double> coordinates(static_cast<Eigen::Index>(rest.size()), 3);
  coordinates.setFromTriplets(xyz.begin(), xyz.end());
  write_matrix_market(dir / "X0.mtx", coordinates);
  levels[0]["coordinates"] = {{"file", "X0.mtx"}, {"rows", rest.size()}, {"cols", 3}};
  const nlohmann::json record = {
      {"producer", "corofem export-matrices"},
      {"context", run_context()},
      {"scene_file", scene.name},
      {"dof_index", "3 * vertex + component"},
      {"matrix", a.type == AnalysisType::Static
                     ? "Ktilde with supports imposed, first iteration"
                     : "M + dt C + dt^2 Ktilde with supports imposed, first step"},
      {"levels", levels}};
  write_file_atomically(dir / "levels.json", [&](std::ostream& o) { o << record.dump(1) << '\n'; });
}

}  // namespace corofem
