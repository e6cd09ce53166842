#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "mesh/gmsh_mesh.hpp"

namespace corofem::test {
namespace fs = std::filesystem;

void randomize_symmetric(BrcMatrix& a, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& v : a.values) v = u(rng);
  for (int i = 0; i < a.block_rows; ++i)
    for (int b = a.row_start[i]; b < a.row_start[i + 1]; ++b)
      if (a.col_index[b] < i) {
        a.block(b) = a.block(a.find(a.col_index[b], i)).transpose();
      } else if (a.col_index[b] == i) {
        const Eigen::Matrix3d d = a.block(b);
        a.block(b) = 0.5 * (d + d.transpose());
      }
}

BrcMatrix random_spd_brc(int n, std::mt19937& rng) {
  std::uniform_int_distribution<int> column(0, n - 1), count(0, 12);
  std::vector<std::vector<int>> columns(n);
  for (int i = 0; i < n; ++i) {
    columns[i].push_back(i);
    for (int k = count(rng); k > 0; --k) {
      const int j = column(rng);
      columns[i].push_back(j);
      columns[j].push_back(i);
    }
  }
  for (std::vector<int>& c : columns) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  BrcMatrix a = make_brc_pattern(n, columns);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < n; ++i)
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      const int j = a.col_index[k];
      if (j > i) continue;
      Eigen::Matrix3d b =
          Eigen::Matrix3d::NullaryExpr([&](Eigen::Index, Eigen::Index) { return u(rng); });
      if (j == i)
        b = (b + b.transpose()).eval() +
            3.0 * (a.row_start[i + 1] - a.row_start[i]) * Eigen::Matrix3d::Identity();
      a.block(k) = b;
      a.block(a.find(j, i)) = b.transpose();
    }
  return a;
}

Eigen::MatrixXd dense_copy(const BrcMatrix& a) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3 * a.block_rows, 3 * a.block_cols);
  for (int i = 0; i < a.block_rows; ++i)
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k)
      d.block<3, 3>(3 * i, 3 * a.col_index[k]) = a.block(k);
  return d;
}

TempDir::TempDir() {
  std::random_device rd;
  path_ = fs::temp_directory_path() /
          ("corofem-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_mesh_refused(const fs::path& file, const std::string& fragment) {
  try {
    read_volume_mesh(file);
    ADD_FAILURE() << "no error for " << file;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

CliResult run_cli(const std::string& args, const std::string& launcher) {
  return run_command(without_mpi_singleton() + launcher + (launcher.empty() ? "" : " ") + "'" +
                     COROFEM_CLI + "' " + args);
}

CliResult run_command(const std::string& shell_command) {
  TempDir dir;
  const std::string command =
      shell_command + " > '" + (dir / "out").string() + "' 2> '" + (dir / "err").string() + "'";
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_text(dir / "out");
  result.err = read_text(dir / "err");
  return result;
}

std::string without_mpi_singleton() {
  // A test that ran PETSc in this process made it an MPI singleton, whose Open MPI and PMIx
  // variables (OMPI_MCA_ess=singleton, PMIX_SERVER_URI...) would tell a child corofem or mpirun
  // that it runs inside that job.
  std::string unset;
  for (char** e = environ; *e; ++e) {
    const char* equals = std::strchr(*e, '=');
    const std::string name(*e, equals ? static_cast<std::size_t>(equals - *e) : 0);
    const bool mpi = name.rfind("OMPI_", 0) == 0 || name.rfind("PMIX_", 0) == 0;
    if (mpi && name != "OMPI_ALLOW_RUN_AS_ROOT" && name != "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM" &&
        name != "OMPI_MCA_rmaps_base_oversubscribe")
      unset += " -u " + name;
  }
  return unset.empty() ? "" : "env" + unset + " ";
}

std::string mpirun_ranks(int ranks) {
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  setenv("OMPI_MCA_rmaps_base_oversubscribe", "1", 1);
  return "mpirun -np " + std::to_string(ranks);
}

std::string mpirun_two_ranks() {
  return mpirun_ranks(2);
}

fs::path source_dir() {
  return COROFEM_SOURCE_DIR;
}

fs::path models_dir() {
  if (const char* env = std::getenv("COROFEM_MODELS"); env && *env)
    return fs::is_directory(env) ? fs::path(env) : fs::path();
  const fs::path shared = source_dir().parent_path() / "shared" / "models";
  return fs::is_directory(shared) ? shared : fs::path();
}

bool full_sweep() {
  const char* env = std::getenv("COROFEM_FULL");
  return env && std::string(env) == "1";
}

std::string cube_stl(int n, const Vec3& origin, double side) {
  return box_stl({n, n, n}, side * Mat3::Identity(), origin);
}

std::string box_stl(const std::array<int, 3>& cells, const Mat3& edges, const Vec3& origin) {
  std::string s = "solid box\n";
  auto point = [&](const Vec3& unit) {
    const Vec3 p = origin + edges * unit;
    return "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
           std::to_string(p.z()) + "\n";
  };
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    s +=
        "facet normal 0 0 0\nouter loop\n" + point(a) + point(b) + point(c) + "endloop\nendfacet\n";
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const Vec3 normal = (side ? 1.0 : -1.0) * Vec3::Unit(axis);
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const Vec3 eu = Vec3::Unit(u) / cells[u], ev = Vec3::Unit(v) / cells[v];
      const bool flip = eu.cross(ev).dot(normal) < 0;
      for (int i = 0; i < cells[u]; ++i)
        for (int j = 0; j < cells[v]; ++j) {
          const Vec3 o = side * Vec3::Unit(axis) + i * eu + j * ev;
          const Vec3 a = o, b = o + eu, c = o + eu + ev, d = o + ev;
          if (flip) {
            tri(a, c, b);
            tri(a, d, c);
          } else {
            tri(a, b, c);
            tri(a, c, d);
          }
        }
    }
  return s + "endsolid box\n";
}

Mat12 dense_element_stiffness(const FeProblem& p, int e) {
  const Tet& t = p.mesh.tets[e];
  return element_stiffness(p.mesh.rest[t[0]], p.mesh.rest[t[1]], p.mesh.rest[t[2]],
                           p.mesh.rest[t[3]], p.materials[e]);
}

}  // namespace corofem::test
