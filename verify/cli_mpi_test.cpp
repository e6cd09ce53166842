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
    const std::string scene = "'" + (dir / "bar.json").string() + "'";
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
}

TEST(CliMpi, ScalingScriptRecordsEveryConfiguration) {
  // bench/mpi_scaling.py --smoke: the strong and weak studies at 1 and 2 ranks (threads for
  // mgpcg) on small bars; the report renders its record.
  if (!have_petsc()) GTEST_SKIP() << "this build has no PETSc: no distributed solver to scale";
  ASSERT_NO_FATAL_FAILURE(require_mpirun());
  TempDir dir;
  const std::filesystem::path bin = std::filesystem::path(COROFEM_CLI).parent_path();
  const std::string command = "python3 '" +
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
