#pragma once
// Shared fixtures of the benchmarks: the paper-sized meshes, built once per process.
#include <filesystem>
#include <functional>
#include <string>

#include "fem/fe_problem.hpp"
#include "multigrid/hierarchy_builder.hpp"
#include "scene/scene.hpp"

namespace corofem::bench {

/// Wall time of one call of f, in ms (for ratios of kernels alternated within one run).
double time_ms(const std::function<void()>& f);
/// The same after two untimed calls of f. On these machines a kernel's first two runs after
/// another kernel are slow (BM_ThreadScaling at --threads 1, a kernel against itself, first
/// timed against second: the product 1.39 against 0.59 ms after one untimed run, 0.56 against
/// 0.66 after two), which had made the gather look 0.77x the stream on the dragon when timed
/// after the full stream; the cause is not known (no counters here). Timed this way, the
/// kernels alternated in one run are compared in the state a step repeats.
double warm_time_ms(const std::function<void()>& f);

/// Writes one byte a cache line over a buffer larger than this machine's last-level cache
/// (260 MiB here), so the next kernel finds its data in memory, as a step's assembly does after
/// the Galerkin stream.
void evict_caches();

void set_models_dir(const std::filesystem::path& dir);
const std::filesystem::path& models_dir();

/// Paper-sized problems by name: "bunny" (~11k tets), "horse" (~34k), "dragon" (~67k). With a
/// models folder the surfaces are tetrahedralized at the sizes of the models' README; without,
/// boxes of about the same tet counts; surface meshes sorted for locality, as the report's are.
/// Cached: built once per process.
FeProblem& paper_problem(const std::string& model);

/// Levels of the paper's hierarchies: bunny 3, horse 4, dragon 4.
int paper_levels(const std::string& model);

/// The mesh of paper_problem as a scene's mesh spec; with a models folder its coarse levels are
/// the models' L1 and L2 surfaces at the sizes of their README.
MeshSpec paper_mesh_spec(const std::string& model);

/// Levels of the hierarchy a benchmark runs: the paper's, except on the models' meshes, which
/// ship two coarse surfaces (a fourth level re-meshed from L2 keeps L2's surface vertices and
/// would barely coarsen).
int hierarchy_levels(const std::string& model, HierarchyKind kind);

/// The transfers of the model's hierarchy of the given kind (x-min face fixed, as paper_system).
/// With `bare_surface`: the meshes derived from the fine surface alone (no L1, L2), as a user's
/// bare STL gets them.
BuiltHierarchy paper_transfers(const std::string& model, HierarchyKind kind,
                               bool bare_surface = false);

/// The corotated system of the bent state with the x-min face fixed, as a solver sees it
/// (supports imposed), and a right-hand side (gravity). Cached per model.
struct PaperSystem {
  BrcMatrix matrix;
  Eigen::VectorXd rhs;
  std::vector<char> fixed;  ///< per vertex
};
const PaperSystem& paper_system(const std::string& model);

/// Two consecutive frames of a real simulation of the problem: a soft body (E = 1e5 Pa) fixed at
/// its x-min face, sagging under gravity with implicit Euler (dt = 0.01 s, polar rotations,
/// CHOLMOD); `previous` is step 7 and `current` step 8. The rotation change between the two
/// frames is what a warm start has to cover; the rotation benchmark reports it.
/// Cached per model.
struct SimulatedFrames {
  Eigen::VectorXd previous, current;
};
const SimulatedFrames& simulated_frames(const std::string& model);

/// A deformed state of the problem: a bend and twist large enough to rotate elements by tens
/// of degrees (a "real frame" stand-in until the simulated frames of the rotation issue).
Eigen::VectorXd bent_displacement(const FeProblem& problem);

}  // namespace corofem::bench
