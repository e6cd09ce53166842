#pragma once
// Helpers shared by the gates: temporary folders, running the CLI, small meshes, tolerances.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "fem/fe_problem.hpp"
#include "mesh/tet_mesh.hpp"
#include "sparse/block_kernels.hpp"
#include "sparse/brc_matrix.hpp"

// The sanitizer build (its shadow memory and quarantine change every resident-set size).
#if defined(__SANITIZE_ADDRESS__)
#define COROFEM_ASAN_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COROFEM_ASAN_BUILD 1
#endif
#endif

namespace corofem::test {

/// A fresh empty folder under the system temp dir, removed at destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// A BRC matrix as a dense one, block by block: the oracle of the sparse passes and conversions.
Eigen::MatrixXd dense_copy(const BrcMatrix& a);
/// Symmetric pattern (block (j, i) wherever (i, j)) with the diagonal and up to 12 random blocks
/// per row; values of an SPD matrix: a random symmetric one plus a dominant diagonal.
BrcMatrix random_spd_brc(int n, std::mt19937& rng);
/// Random symmetric values on A's (symmetric) pattern: A_ji = A_ij^T bit for bit, as every
/// system matrix (the symmetric stream's mirror relies on it).
void randomize_symmetric(BrcMatrix& a, std::mt19937& rng);

struct CliResult {
  int exit_code;
  std::string out, err;
};

/// Runs the corofem binary with `args` (a shell-quoted string), behind `launcher` if given
/// ("mpirun -np 2").
CliResult run_cli(const std::string& args, const std::string& launcher = "");
/// Runs a shell command line, its stdout and stderr captured.
CliResult run_command(const std::string& shell_command);

/// "mpirun -np N". Open MPI refuses root without two variables (CI runs as root) and machines
/// with fewer cores than ranks without oversubscription; all three are set for the launched
/// processes only.
std::string mpirun_ranks(int ranks);
/// "env -u VAR ... " for Open MPI's and PMIx's variables in this process (an MPI singleton's,
/// where a test ran PETSc in it), but the three mpirun_ranks sets; "" when there are none. Put
/// before a command that launches corofem or mpirun; run_cli does.
std::string without_mpi_singleton();
/// mpirun_ranks(2).
std::string mpirun_two_ranks();

void write_text(const std::filesystem::path& file, const std::string& text);
std::string read_text(const std::filesystem::path& file);
/// Expects read_volume_mesh to refuse `file` with an InputError naming the file and containing
/// `fragment`.
void expect_mesh_refused(const std::filesystem::path& file, const std::string& fragment);

/// Element e's dense 12x12 K_e from its rest vertices and material (element_stiffness), the
/// oracle the assembly kernels are held to.
Mat12 dense_element_stiffness(const FeProblem& p, int e);

/// The models folder (COROFEM_MODELS, else ../shared/models beside the source tree), or empty.
std::filesystem::path models_dir();

/// True when COROFEM_FULL=1: the full sweep instead of the fast default.
bool full_sweep();

/// Unit cube surface as ASCII STL, each face split into n x n squares of 2 outward triangles
/// (gmsh keeps the surface triangles, so they set the interior size too); scaled by `side`, its
/// corner at `origin`.
std::string cube_stl(int n, const Vec3& origin = Vec3::Zero(), double side = 1);

/// The parallelepiped origin + edges * [0, 1]^3 (det(edges) > 0) as ASCII STL, the faces split
/// into cells[a] x cells[b] parallelograms of 2 outward triangles along edges a and b.
std::string box_stl(const std::array<int, 3>& cells, const Mat3& edges, const Vec3& origin);

/// Source tree root (for scene files in bench/scenes).
std::filesystem::path source_dir();

/// Runs `body` once in each form of the block kernels this CPU has (scalar, and AVX2 where it
/// has it: sparse/block_kernels.hpp), each traced by name; restores the form in use after.
template <class F>
void in_each_kernel_form(const F& body) {
  const bool before = vector_block_kernels();
  for (const bool vector : {false, true}) {
    set_vector_block_kernels(vector);
    if (vector != vector_block_kernels()) {
      std::cout
          << "[   NOTE   ] this CPU has no AVX2/FMA: only the scalar block kernels are checked\n";
      continue;
    }
    SCOPED_TRACE(block_kernels_name());
    body();
  }
  set_vector_block_kernels(before);
}

}  // namespace corofem::test
