// `mpirun -np 2 corofem run`: the PETSc and hypre solvers distribute their solves over the ranks,
// and the result equals the one-rank run. Where the build has no PETSc (the sanitizer build), a
// launch on two ranks is bad input with a message saying why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rotation/rotation_method.hpp"
#include "scene/analysis_settings.hpp"
#include "solver/petsc_solver.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::run_cli;
using test::TempDir;
using test::write_text;

bool have_mpirun() {
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
}

/// Where the build has PETSc, mpirun must be there too (ci/setup installs it with petsc-dev).
void require_mpirun() {
  ASSERT_TRUE(have_mpirun()) << "mpirun is missing (ci/setup installs it with petsc-dev)";
}

/// A cantilever bar under gravity, 6 implicit Euler steps, solved to a relative residual of
/// 1e-12 by `solver` on a three-level hierarchy (petsc-mg's).
nlohmann::json dynamic_bar(const std::string& solver) {
  return {{"mesh", {{"box", {1.0, 0.2, 0.2}}, {"cells", {20, 4, 4}}}},
          {"material", {{"young", 5e6}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {0, 0.2, 0.2}}}}}},
          {"gravity", {0, 0, -9.81}},
          {"analysis",
           {{"type", "dynamic"},
            {"rotation", "energy-newton"},
            {"solver", solver},
            {"levels", 3},
            {"dt", 0.01},
            {"steps", 6},
            {"tolerance", 1e-12}}}};
}

/// dynamic_bar on petsc-mg, coarser (12x3x3 cells), for the runs at 1, 2 and 3 ranks.
nlohmann::json small_distributed_bar() {
  nlohmann::json scene = dynamic_bar("petsc-mg");
  scene["mesh"]["cells"] = {12, 3, 3};
  return scene;
}

/// A corotated cantilever bent by an end load in two increments, to |f - f_int| / |f| <=
/// `tolerance` by `integrator`, on CHOLMOD (a test swaps the solver).
nlohmann::json static_bar(const std::string& rotation, const std::string& integrator,
                          double tolerance) {
  return {{"mesh", {{"box", {1.0, 0.2, 0.2}}, {"cells", {12, 3, 3}}}},
          {"material", {{"young", 5e6}, {"poisson", 0.3}, {"density", 1000}}},
          {"fixed", {{{"box", {{0, 0, 0}, {0, 0.2, 0.2}}}}}},
          {"forces", {{{"box", {{1, 0, 0}, {1, 0.2, 0.2}}}, {"total", {0, 0, -400}}}}},
          {"analysis",
           {{"type", "static"},
            {"integrator", integrator},
            {"rotation", rotation},
            {"solver", "cholmod"},
            {"levels", 3},
            {"load_steps", 2},
            {"tolerance", tolerance},
            {"max_iterations", 200}}}};
}

std::vector<double> displacements(const nlohmann::json& record) {
  std::vector<double> u;
  for (const auto& v : record["displacement"])
    for (const auto& c : v) u.push_back(c.get<double>());
  return u;
}

TEST(CliMpi, TwoRanksEqualOneRankOnADynamicScene) {
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  for (const std::string solver : {"petsc-gamg", "hypre-boomeramg", "petsc-mg"}) {
    SCOPED_TRACE(solver);
    TempDir dir;
    write_text(dir / "bar.json", dynamic_bar(solver).dump());
    const std::string scene = std::string("'") + (dir / "bar.json").string() +
                              "'";  // not "'" + string: GCC 12's false -Wstringop-overflow
    const auto one = run_cli("run " + scene + " --out '" + (dir / "one.json").string() + "'");
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const auto two = run_cli("run " + scene + " --out '" + (dir / "two.json").string() + "'",
                             test::mpirun_two_ranks());
    ASSERT_EQ(two.exit_code, 0) << two.err;
    const auto a = nlohmann::json::parse(test::read_text(dir / "one.json"));
    const auto b = nlohmann::json::parse(test::read_text(dir / "two.json"));
    EXPECT_EQ(a["mpi"]["ranks"], 1);
    EXPECT_EQ(b["mpi"]["ranks"], 2);
    // Rank 0 alone writes and reports progress: one closing line ("6 steps, ..."), not two.
    const std::string& err = two.err;
    const std::string closing = "solver iterations per step";
    ASSERT_NE(err.find(closing), std::string::npos) << err;
    EXPECT_EQ(err.find(closing), err.rfind(closing)) << err;
    // Each run solves every step to |r| / |b| <= 1e-12 with its own partition (GAMG aggregates
    // and BoomerAMG coarsens per rank), so they agree to about cond(A) 1e-12; the bar's dynamic
    // system (mass over dt^2 plus K) has cond(A) of order 1e2, and the runs differ by 1e-14.
    const std::vector<double> u1 = displacements(a), u2 = displacements(b);
    ASSERT_EQ(u1.size(), u2.size());
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < u1.size(); ++i) {
      diff = std::max(diff, std::abs(u1[i] - u2[i]));
      scale = std::max(scale, std::abs(u1[i]));
    }
    ASSERT_GT(scale, 1e-4);  // the bar sags: the comparison is not of two zeros
    EXPECT_LE(diff, 1e-10 * scale);
  }
}

/// Every rank count's run of `scene` (written to dir/NAME.json) as RESULT.json; 1: no mpirun.
nlohmann::json run_on_ranks(const TempDir& dir, const nlohmann::json& scene, int ranks,
                            const std::string& name) {
  write_text(dir / (name + ".json"), scene.dump());
  // A rank left waiting in a collective that another skipped would hang the run: bounded, it
  // fails (exit 124). These runs take seconds.
  const auto r = run_cli("run '" + (dir / (name + ".json")).string() + "' --out '" +
                             (dir / (name + "_out.json")).string() + "'",
                         ranks > 1 ? "timeout 300 " + test::mpirun_ranks(ranks) : "");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return nullptr;
  return nlohmann::json::parse(test::read_text(dir / (name + "_out.json")));
}

/// max |u - v| over max |u|, asserting the fields are of one mesh and not zero.
double relative_difference(const nlohmann::json& a, const nlohmann::json& b) {
  const std::vector<double> u = displacements(a), v = displacements(b);
  EXPECT_EQ(u.size(), v.size());
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < u.size() && i < v.size(); ++i) {
    diff = std::max(diff, std::abs(u[i] - v[i]));
    scale = std::max(scale, std::abs(u[i]));
  }
  EXPECT_GT(scale, 1e-4);  // the bar sags: the comparison is not of two zeros
  return diff / scale;
}

/// `scene` run by serial CHOLMOD, then as it is at 1, 2 and 3 ranks: each run's displacements
/// within `tolerance` of CHOLMOD's |u|. Returns the runs at 1, 2, 3 ranks (fewer where one failed,
/// which is a test failure).
std::vector<nlohmann::json> runs_against_cholmod(const TempDir& dir, const nlohmann::json& scene,
                                                 double tolerance) {
  nlohmann::json serial = scene;
  serial["analysis"]["solver"] = "cholmod";
  const nlohmann::json cholmod = run_on_ranks(dir, serial, 1, "cholmod");
  std::vector<nlohmann::json> runs;
  if (cholmod.is_null()) return runs;
  for (int ranks : {1, 2, 3}) {
    SCOPED_TRACE(ranks);
    nlohmann::json r = run_on_ranks(dir, scene, ranks, "ranks");
    if (r.is_null()) break;
    EXPECT_LE(relative_difference(cholmod, r), tolerance);
    runs.push_back(std::move(r));
  }
  return runs;
}

TEST(CliMpi, DistributedMeshAgreesAtOneTwoAndThreeRanksWithCholmodForEveryRotation) {
  // Under mpirun a dynamic linearly implicit scene runs on a distributed mesh: each rank rotates
  // and assembles its part only. Every rotation method (polar-smoothed needs a ring of tets more
  // per smoothing pass) must give the serial CHOLMOD answer. Each solve stops at |r| / |b| <=
  // 1e-12 and the bar's dynamic system has cond(A) of order 1e2: the runs agree to 1e-10 of |u|
  // (measured 1e-15); one rotation computed without a neighbour, or a row missing one tet's
  // contribution, is off by 1e-5 or more.
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  for (const std::string& name : rotation_method_names()) {
    SCOPED_TRACE(name);
    nlohmann::json scene = small_distributed_bar();
    scene["analysis"]["steps"] = 3;
    scene["analysis"]["rotation"] = name;
    const std::vector<nlohmann::json> runs = runs_against_cholmod(dir, scene, 1e-10);
    ASSERT_EQ(runs.size(), 3u);
    for (std::size_t ranks = 2; ranks <= runs.size(); ++ranks) {
      const nlohmann::json& r = runs[ranks - 1];
      EXPECT_NE(r["mpi"]["distributed"].get<std::string>().find("the mesh"), std::string::npos);
      EXPECT_EQ(r["ranks"]["per_rank"].size(), ranks);
    }
  }
}

TEST(CliMpi, MovedAndReleasedSupportsOnADistributedMeshEqualCholmodAtOneTwoAndThreeRanks) {
  // The bar's tip is moved for three steps and released at the fourth: a change of supports in
  // the last rank's part only. Small strain hands the solver a matrix only when the supports
  // change, and every rank must take it (the update is collective: a rank that skips it hangs the
  // run, bounded by run_on_ranks); corotated, every step's matrix carries the supports. Same
  // bounds as the corotated runs above (cond(A) of order 1e2, each solve to 1e-12).
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  for (const auto& [formulation, name] : kFormulations.entries) {
    SCOPED_TRACE(name);
    nlohmann::json scene = small_distributed_bar();
    scene["analysis"]["formulation"] = name;
    scene["moves"] = {{{"box", {{1, 0, 0}, {1, 0.2, 0.2}}},
                       {"translate", {0, 0, 0.05}},
                       {"ramp_steps", 2},
                       {"release_step", 4}}};
    EXPECT_EQ(runs_against_cholmod(dir, scene, 1e-10).size(), 3u);
  }
}

TEST(CliMpi, StaticSceneOnADistributedMeshEqualsCholmodAtOneTwoAndThreeRanks) {
  // A static corotated cantilever by the lagged iteration (the residual norms summed over the
  // ranks' owned rows) to |f - f_int| / |f| <= 1e-12: every run stops at the same fixed point,
  // so the ranks agree with CHOLMOD far inside 1e-8 of |u| (measured 2e-16); a norm taken over
  // one rank's rows only would stop the ranks at different iterations, or not at all.
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  for (const char* rotation : {"polar", "energy-newton"}) {
    SCOPED_TRACE(rotation);
    nlohmann::json scene = static_bar(rotation, "linear-implicit", 1e-12);
    scene["analysis"]["solver"] = "petsc-mg";
    const std::vector<nlohmann::json> runs = runs_against_cholmod(dir, scene, 1e-8);
    ASSERT_EQ(runs.size(), 3u);
    for (std::size_t ranks = 1; ranks <= runs.size(); ++ranks) {
      SCOPED_TRACE(ranks);
      const nlohmann::json& r = runs[ranks - 1];
      EXPECT_TRUE(r["converged"].get<bool>());
      if (ranks > 1) {
        EXPECT_NE(r["mpi"]["distributed"].get<std::string>().find("the mesh"), std::string::npos);
      }
    }
  }
}

TEST(CliMpi, TwoRanksEachHoldTheirPartOfTheMeshAndWriteItsPiece) {
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  nlohmann::json scene = dynamic_bar("petsc-gamg");
  scene["analysis"]["steps"] = 2;
  scene["output"] = {{"vtu", "bar.vtu"}};
  const nlohmann::json r = run_on_ranks(dir, scene, 2, "bar");
  ASSERT_FALSE(r.is_null());
  const int tets = r["mesh"]["tets"], vertices = r["mesh"]["vertices"];
  EXPECT_EQ(tets, 6 * 20 * 4 * 4);
  EXPECT_EQ(r["displacement"].size(), static_cast<std::size_t>(vertices));  // gathered on rank 0
  const auto& per_rank = r["ranks"]["per_rank"];
  ASSERT_EQ(per_rank.size(), 2u);
  double owned_tets = 0, owned_vertices = 0;
  for (const auto& rank : per_rank) {
    SCOPED_TRACE(rank.dump());
    owned_tets += rank["owned_tets"].get<double>();
    owned_vertices += rank["owned_vertices"].get<double>();
    // No rank holds the whole mesh: its own half and a halo a few layers deep.
    EXPECT_LT(rank["held_tets"].get<double>(), 0.75 * tets);
    EXPECT_GE(rank["held_tets"].get<double>(), rank["owned_tets"].get<double>());
    EXPECT_GT(rank["halo_vertices"].get<double>(), 0);
    EXPECT_GT(rank["peak_rss_kb"].get<double>(), 0);
    EXPECT_GT(rank["rotate_ms"].get<double>(), 0);
  }
  // Rank 0 alone built the whole body; rank 1 received its part and never held the rest.
  EXPECT_EQ(per_rank[0]["built_whole_body"], 1.0);
  EXPECT_EQ(per_rank[1]["built_whole_body"], 0.0);
  EXPECT_EQ(owned_tets, tets);
  EXPECT_EQ(owned_vertices, vertices);
  // PT-Scotch cuts the 20-cell bar across: each rank's halo is one cross-section of 5 x 5
  // vertices, two at most (equal shares of the Morton order gave 127 vertices, five).
  EXPECT_EQ(r["ranks"]["partitioner"], "PT-Scotch (PETSc MatPartitioning)");
  EXPECT_LE(r["ranks"]["max"]["halo_vertices"].get<double>(), 2 * 5 * 5);
  EXPECT_EQ(r["ranks"]["max"]["held_tets"], std::max(per_rank[0]["held_tets"].get<double>(),
                                                     per_rank[1]["held_tets"].get<double>()));
  // A parallel VTU: the .pvtu names a piece per rank, whose cells are the rank's owned tets.
  ASSERT_TRUE(std::filesystem::exists(dir / "bar.pvtu"));
  const std::string pvtu = test::read_text(dir / "bar.pvtu");
  int cells = 0;
  for (int rank = 0; rank < 2; ++rank) {
    const std::string piece = "bar_r" + std::to_string(rank) + ".vtu";
    EXPECT_NE(pvtu.find("Source=\"" + piece + "\""), std::string::npos) << pvtu;
    const std::string text = test::read_text(dir / piece);
    const std::size_t at = text.find("NumberOfCells=\"");
    ASSERT_NE(at, std::string::npos);
    cells += std::stoi(text.substr(at + 15));
  }
  EXPECT_EQ(cells, tets);
}

/// Runs `scene` on two ranks: exit 2, `message` said once (by rank 0, not once per rank), no
/// record written.
void expect_bad_input_said_once(const nlohmann::json& scene, const std::string& message) {
  TempDir dir;
  write_text(dir / "bad.json", scene.dump());
  const auto r =
      run_cli("run '" + (dir / "bad.json").string() + "' --out '" + (dir / "r.json").string() + "'",
              test::mpirun_two_ranks());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  ASSERT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(message), r.err.rfind(message)) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
}

TEST(CliMpi, StaticNewtonOnPetscSolversEqualsTheSparseLuNewtonForEveryRotation) {
  // Static Newton with a PETSc solver: its GMRES solves the corotated tangent (MUMPS's LU where
  // GMRES misses), on one process and on a distributed mesh, where each rank assembles the tangent
  // of its part. Against Newton on the sparse factorizations (CHOLMOD's scene) to |g| / |f| <=
  // 1e-10: both converge quadratically to the same fixed point, so they agree far inside 1e-8 of
  // |u| (measured 4e-13). A force row missing a tet moves the fixed point by 1e-3 or more; a
  // tangent row missing one would still reach it (the forces set it), but in more Newton
  // iterations: hence the equal iteration counts.
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  for (RotationMethod method : rotation_methods()) {
    const std::string& name = method.name();
    SCOPED_TRACE(name);
    nlohmann::json scene = static_bar(name, "newton", 1e-10);
    const nlohmann::json serial = run_on_ranks(dir, scene, 1, "serial");
    ASSERT_FALSE(serial.is_null());
    ASSERT_TRUE(serial["converged"].get<bool>());
    scene["analysis"]["solver"] = method == RotationMethod::Polar ? "petsc-gamg" : "petsc-mg";
    EXPECT_EQ(serial["analysis"]["solver"], "sparse LU (UMFPACK), Newton");
    for (int ranks : {1, 2, 3}) {
      SCOPED_TRACE(ranks);
      const nlohmann::json r = run_on_ranks(dir, scene, ranks, "newton");
      ASSERT_FALSE(r.is_null());
      EXPECT_TRUE(r["converged"].get<bool>());
      EXPECT_LE(relative_difference(serial, r), 1e-8);
      EXPECT_EQ(r["iterations"], serial["iterations"]);
      EXPECT_NE(r["analysis"]["solver"].get<std::string>().find("GMRES"), std::string::npos);
      if (ranks > 1) {
        EXPECT_NE(r["mpi"]["distributed"].get<std::string>().find("the mesh"), std::string::npos);
      }
    }
  }
}

TEST(CliMpi, BadInputOnTwoRanksExits2WithOneMessage) {
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  nlohmann::json scene = dynamic_bar("petsc-gamg");
  scene["mesh"] = {{"file", "missing.msh"}};
  expect_bad_input_said_once(scene, "missing.msh");
  // Found while rank 0 alone builds the body: the other rank, waiting for its part, stops too.
  scene = dynamic_bar("petsc-gamg");
  scene["fixed"][0]["box"] = {{5, 5, 5}, {6, 6, 6}};
  expect_bad_input_said_once(scene, "fixed[0].box selects no vertex");
}

TEST(CliMpi, SerialSolverUnderMpirunIsBadInput) {
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: CliMpi.TwoRanksNeedPetsc covers it";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  write_text(dir / "bar.json", dynamic_bar("mgpcg").dump());
  const auto r =
      run_cli("run '" + (dir / "bar.json").string() + "' --out '" + (dir / "r.json").string() + "'",
              test::mpirun_two_ranks());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("analysis.solver 'mgpcg' under mpirun -np 2"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
  // Dynamic Newton's serial factorization, with a distributed solver: refused, naming the way out.
  nlohmann::json newton = dynamic_bar("petsc-gamg");
  newton["analysis"]["integrator"] = "newton";
  write_text(dir / "newton.json", newton.dump());
  const auto n = run_cli(
      "run '" + (dir / "newton.json").string() + "' --out '" + (dir / "r.json").string() + "'",
      test::mpirun_two_ranks());
  EXPECT_EQ(n.exit_code, 2);
  EXPECT_NE(n.err.find("analysis.integrator 'newton'"), std::string::npos) << n.err;
  EXPECT_NE(n.err.find("'linear-implicit'"), std::string::npos) << n.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
}

TEST(CliMpi, ScalingScriptRecordsEveryConfiguration) {
  // bench/mpi_scaling.py --smoke: the strong and weak studies at 1 and 2 ranks (threads for
  // mgpcg) on small bars; the report renders its record.
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: no distributed solver to scale";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  const std::filesystem::path bin = std::filesystem::path(COROFEM_CLI).parent_path();
  const std::string command = test::without_mpi_singleton() + "python3 '" +
                              (test::source_dir() / "bench" / "mpi_scaling.py").string() +
                              "' --smoke --bin '" + bin.string() + "' --out '" +
                              (dir / "s.json").string() + "' 2> '" + (dir / "err").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << test::read_text(dir / "err");
  const auto s = nlohmann::json::parse(test::read_text(dir / "s.json"));
  EXPECT_TRUE(s["context"].contains("commit"));
  // Four solvers: rank (or thread) counts 1 and 2 on the base bar, and 2 on the doubled bar.
  ASSERT_EQ(s["runs"].size(), 12u);
  // Every run of one bar solves the same steps, each solve to a relative residual of 1e-4: the
  // displacements agree to that times the steps' small condition number (the mass term). 1e-3
  // of |u| allows a factor 10; a rank that dropped its rows' contributions, or a solve stopped
  // early, is off by far more.
  std::map<int, double> displacement_of_bar;  // tets -> the first run's |u|
  for (const auto& r : s["runs"]) {
    SCOPED_TRACE(r.dump());
    EXPECT_TRUE(r["converged"].get<bool>());
    EXPECT_GT(r["linear_iterations_per_step"].get<double>(), 0);
    // The phases are timed inside the step: together they take at most the step (a phase timed
    // twice or outside its step breaks this).
    const auto& ms = r["ms_per_step"];
    double phases = 0;
    for (const char* phase : {"rotate", "assemble", "update", "solve"}) {
      ASSERT_TRUE(ms.contains(phase)) << phase;
      EXPECT_GE(ms[phase].get<double>(), 0) << phase;
      phases += ms[phase].get<double>();
    }
    EXPECT_LE(phases, ms["step"].get<double>() * (1 + 1e-9));
    const int workers = r["solver"] == "mgpcg" ? r["threads"].get<int>() : r["ranks"].get<int>();
    EXPECT_EQ(r["solver"] == "mgpcg" ? r["ranks"].get<int>() : r["threads"].get<int>(), 1);
    // The weak study's bar has `workers` times the base bar's cells along x: the tets scale with
    // it.
    const int tets = r["tets"].get<int>();
    EXPECT_EQ(tets, (r["study"] == "weak" ? workers : 1) * 6 * 8 * 4 * 4);
    const double u = r["displacement_norm"].get<double>();
    EXPECT_GT(u, 0);
    const auto [first, inserted] = displacement_of_bar.emplace(tets, u);
    EXPECT_NEAR(u, first->second, 1e-3 * first->second) << r["solver"] << " at " << workers;
  }
  EXPECT_EQ(displacement_of_bar.size(), 2u);  // the base bar and the doubled one
}

TEST(CliMpi, TwoRanksNeedPetsc) {
  if (have_petsc())
    GTEST_SKIP() << "this build has PETSc: CliMpi.TwoRanksEqualOneRankOnADynamicScene covers it";
  if (!have_mpirun()) GTEST_SKIP() << "no mpirun to launch two ranks with";
  TempDir dir;
  write_text(dir / "bar.json", dynamic_bar("petsc-gamg").dump());
  const auto r =
      run_cli("run '" + (dir / "bar.json").string() + "' --out '" + (dir / "r.json").string() + "'",
              test::mpirun_two_ranks());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("has no PETSc and so no MPI"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
}

}  // namespace
}  // namespace corofem
