// The smoother registry: the built-ins by name, and a smoother registered from outside lib/
// (l1 block Jacobi, damped) reaching the scene parser, the V-cycle, the record and the roofline
// without a change elsewhere; its MG-PCG answer checked against CHOLMOD. Registration changes the
// process for good, so it runs in a child process (a death test's fork).
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/errors.hpp"
#include "io/solver_record.hpp"
#include "multigrid/multigrid_solver.hpp"
#include "report/step_roofline.hpp"
#include "scene/scene_simulation.hpp"

namespace corofem {
namespace {

using nlohmann::json;

TEST(SmootherRegistry, BuiltInsByName) {
  const std::vector<std::string> expected = {"sequential", "multicolour", "domains", "hybrid",
                                             "chebyshev"};
  ASSERT_GE(smoother_names().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(smoother_names()[k], expected[k]);
  EXPECT_EQ(make_smoother("domains", {})->describe()["ordering"], "domains");
  EXPECT_EQ(make_smoother("chebyshev", {.chebyshev_degree = 4})->describe()["degree"], 4);
  try {
    make_smoother("jacobi", {});
    ADD_FAILURE() << "an unknown smoother was made";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("hybrid"), std::string::npos) << e.what();
  }
}

/// x += w M^-1 (b - A x), M the l1-augmented block diagonal (every eigenvalue of M^-1 A in
/// (0, 1], so any w in (0, 2) converges); the same before and after the coarse correction.
class DampedL1Jacobi : public Smoother {
 public:
  void set_matrix(const BrcMatrix& a) override {
    inverse_.assign(a.block_rows, Mat3::Zero());
    for (int i = 0; i < a.block_rows; ++i) {
      Mat3 d = Mat3::Zero();
      for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
        if (a.col_index[k] == i)
          d += a.block(k);
        else
          d.diagonal() += a.block(k).cwiseAbs().rowwise().sum();
      inverse_[i] = d.inverse();
    }
  }
  bool pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int sweeps,
                  bool zero_guess, Eigen::VectorXd&) const override {
    if (zero_guess) x.setZero(b.size());
    post_smooth(a, b, x, sweeps);
    return false;
  }
  bool forms_residual(int) const override { return false; }
  void post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   int sweeps) const override {
    Eigen::VectorXd r;
    for (int s = 0; s < sweeps; ++s) {
      a.residual(b, x, r);
      for (int i = 0; i < a.block_rows; ++i)
        x.segment<3>(3 * i) += kDamping * (inverse_[i] * r.segment<3>(3 * i));
    }
  }
  Traffic setup_traffic(const BrcMatrix& a) const override {
    return {matrix_bytes(a) + kBlockBytes * a.block_rows, 50.0 * a.block_rows};
  }
  Traffic pre_traffic(const BrcMatrix& a, int sweeps) const override {
    return post_traffic(a, sweeps);
  }
  Traffic post_traffic(const BrcMatrix& a, int sweeps) const override {
    const double n = 3.0 * a.block_rows;
    return sweeps * Traffic{matrix_bytes(a) + 24 * n + kBlockBytes * a.block_rows + 24 * n,
                            18.0 * static_cast<double>(a.col_index.size()) + 21 * n};
  }
  json describe() const override { return {{"kind", "damped-l1-jacobi"}, {"damping", kDamping}}; }

 private:
  static constexpr double kDamping = 0.8;
  std::vector<Mat3> inverse_;
};

json cube_scene(const std::string& solver) {
  return {{"mesh", {{"box", {1, 1, 1}}, {"cells", {6, 6, 6}}}},
          {"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {1e-9, 1, 1}}}}}},
          {"gravity", {0, 0, -9.81}},
          {"analysis",
           {{"type", "static"},
            {"formulation", "linear"},
            {"solver", solver},
            {"levels", 2},
            {"tolerance", 1e-11}}}};
}

void register_and_use_a_smoother_of_ones_own() {
  register_smoother({.name = "damped-l1-jacobi", .make = [](const SmootherSettings&) {
                       return std::unique_ptr<Smoother>(new DampedL1Jacobi);
                     }});
  EXPECT_THROW(
      register_smoother({.name = "damped-l1-jacobi", .make = find_smoother("hybrid")->make}),
      std::invalid_argument);

  json scene = cube_scene("mgpcg");
  scene["analysis"]["smoother"] = "damped-l1-jacobi";
  SceneSimulation mine(parse_scene(scene, ".", "cube.json"));
  const SimulationResult got = mine.run();
  SceneSimulation direct(parse_scene(cube_scene("cholmod"), ".", "cube.json"));
  const SimulationResult want = direct.run();
  // MG-PCG to 1e-11 in the residual: the displacements agree to about the condition number's
  // share of it (1e-8 is that with room).
  EXPECT_LT((got.displacement - want.displacement).norm(), 1e-8 * want.displacement.norm());

  const auto& solver = dynamic_cast<const MultigridSolver&>(mine.solver());
  EXPECT_EQ(to_json(solver.params())["smoother"]["kind"], "damped-l1-jacobi");
  EXPECT_EQ(to_json(solver.params())["smoother"]["damping"], 0.8);
  // The roofline counts its sweeps: a V-cycle on two levels reads the fine matrix once a
  // smoothing and once for the residual, an iteration once more for CG's product.
  const FeProblem& problem = mine.problem();
  const double v = problem.mesh.num_vertices();
  const double blocks = static_cast<double>(problem.stiffness.col_index.size());
  const double fine_matrix = 76 * blocks + 4 * (v + 1);
  const double per_iteration = step_traffic(problem, solver, 0, 6.0).at("solve").bytes -
                               step_traffic(problem, solver, 0, 5.0).at("solve").bytes;
  const double n = 3 * v, cg_vectors = 15 * 8 * n;
  const MultigridHierarchy& h = solver.hierarchy();
  ASSERT_EQ(h.num_levels(), 2);
  const double coarsest =
      16 * solver.coarsest_factor_nonzeros() + 32 * 3.0 * h.matrix(1).block_rows;
  EXPECT_GE(per_iteration, 4 * fine_matrix + cg_vectors + coarsest);
  // Besides: its two sweeps' inverse diagonal and vectors, the transfers (under 200 B a DOF).
  EXPECT_LE(per_iteration,
            4 * fine_matrix + cg_vectors + coarsest + 2 * (72 * v + 48 * n) + 200 * n);
  std::exit(::testing::Test::HasFailure() ? 1 : 0);
}

TEST(SmootherRegistryDeathTest, ASmootherOfOnesOwnIsParsedRunAndCounted) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(register_and_use_a_smoother_of_ones_own(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace corofem
