#pragma once
// Hierarchy builders: the transfers of every level of a multigrid hierarchy, by one of
//  - meshes: coarser tet meshes of the same body, as in the paper (non-nested; mesh_level.hpp);
//  - lattice: covering Kuhn lattices with the cell doubling per level (lattice_level.hpp).
// The parameters are written into every record of a multigrid solve (io/multigrid_record.hpp).
#include <string>
#include <vector>

#include "core/name_table.hpp"
#include "multigrid/mesh_level.hpp"
#include "multigrid/transfer.hpp"

namespace corofem {

enum class HierarchyKind { Meshes, Lattice };
/// The builders' names in scenes and records.
inline constexpr NameTable<HierarchyKind, 2> kHierarchyKinds{
    {{{HierarchyKind::Meshes, "meshes"}, {HierarchyKind::Lattice, "lattice"}}}};

/// HierarchyParams::coarsest_vertices for a hierarchy sized by its fine mesh
/// (coarsest_vertex_limit).
inline constexpr int kCoarsestSizedByFine = -1;

struct HierarchyParams {
  HierarchyKind kind = HierarchyKind::Lattice;
  int levels = 3;  ///< including the fine level; with coarsest_vertices, the most there may be
  /// The levels stop at the first coarse one with at most this many vertices (there is always one
  /// coarse level; `levels` stays the cap). 0: exactly `levels`. kCoarsestSizedByFine: the limit
  /// follows the fine mesh (coarsest_vertex_limit).
  int coarsest_vertices = 0;
  double first_cell_factor = 1.5;  ///< lattice: level-1 cell = factor x mean fine edge length
  /// Below the `levels` levels, lattice levels (cell twice the last level's spacing, doubling)
  /// until the coarsest has at most this many vertices: its factorization, every step, then
  /// costs little (0 = none added). Stops when a lattice level would not halve the vertices.
  int coarsest_max_vertices = 0;
  /// meshes: a coarse mesh must have at most 1/this of the level above's vertices, or it is
  /// replaced, with the levels below it, by lattice levels, and the level's origin says why
  /// (gmsh re-meshing a surface keeps its triangles, which can give a level barely smaller than
  /// the one above and denser in nonzeros). A safety net, not a target: derived
  /// surface levels coarsen 4.7-7x (coarse_surface_mesh.hpp), a thin box's clamped at 2 cells
  /// across about 2x.
  double min_coarsening = 1.5;
  /// A rejected mesh below a level of at most this many vertices ends the hierarchy there
  /// instead (that level's direct factorization costs little; a lattice below a small curved
  /// level, as the quadruped's, slows the V-cycle: stationary cycles stalled at 0.99).
  int end_below_vertices = 2000;
  /// meshes: the coarse meshes the scene derives (re-meshed, not given) are sized to have about
  /// 1/this of the level above's vertices (scene/coarse_meshes.hpp). 0 (the default): the mesh
  /// size doubled per level, whatever that gives: 3.6x fewer vertices on the 11k quadruped, 6.2x
  /// on the 270k one, 6.6x on the bare horse, which is the fastest step there; a fixed ratio (3.5)
  /// makes the quadruped's convergence independent of its size (README "Multigrid").
  double coarsening = 0;
};

/// The level count where a scene gives none: at most this many levels, down to the limit below.
inline constexpr int kSizedHierarchyMaxLevels = 8;

/// The coarsest level's vertex limit for `params` over a fine mesh of `fine_vertices` (0: none).
/// Sized by the fine mesh: sqrt(40 x fine vertices), as the coarsest factorization's flops grow
/// about as the square of its vertices (a 3D sparse Cholesky) and a step's work as the fine
/// vertices. Measured on bare surfaces and the quadruped (lib/docs/multigrid.md, "Levels sized by
/// the scene"): a level more paid below 1,130 vertices of 7,491 (the horse), 2,299 of 15,174 (the
/// dragon) and 405 of 2,653 (the bunny), and cost 5-20% below 223 of 7,491, 466 of 15,174 and
/// 735 of 14,716 (quadruped-67k: even).
int coarsest_vertex_limit(const HierarchyParams& params, int fine_vertices);

/// Where a coarse level came from: a coarse mesh of the body (its size, and how the level above
/// fits in it) or a lattice (its cell).
struct CoarseLevelOrigin {
  enum class Kind { Mesh, Lattice, LatticeBelowCoarsest, LatticeForMesh };
  Kind kind = Kind::Lattice;
  std::string mesh;  ///< Mesh: its name (the source it was read or meshed from)
  int mesh_vertices = 0, mesh_tets = 0;
  MeshLevelFit fit;  ///< Mesh: the level above located in it
  double cell = 0;   ///< Lattice kinds: the cell size
  /// LatticeForMesh: why the mesh of this level was not used (names it and both sizes).
  std::string fallback;
};

struct BuiltHierarchy {
  std::vector<Transfer> transfers;        ///< level h to h + 1
  std::vector<CoarseLevelOrigin> levels;  ///< per coarse level
  /// Why it has fewer levels than asked for (empty when it has them all, or a lattice ran out of
  /// vertices to coarsen).
  std::string ended_early;
};

/// Transfers for `params.levels` levels below the fine mesh (fewer where the coarsest vertex limit
/// is met first). `fixed` per fine vertex (its DOFs take no part in the transfer). Meshes:
/// `coarse_meshes[h - 1]` is level h (at least levels - 1 of them; `names` for messages), down to
/// the first that does not coarsen by params.min_coarsening: lattice levels from there on (fewer
/// meshes than levels - 1 also end the meshes there). Lattice: stops early when nothing is left to
/// coarsen. Then lattice levels down to `params.coarsest_max_vertices`. Throws InputError for a
/// coarse mesh that does not cover the level above.
BuiltHierarchy build_hierarchy(const TetMesh& fine, const std::vector<char>& fixed,
                               const HierarchyParams& params,
                               const std::vector<TetMesh>& coarse_meshes = {});

}  // namespace corofem
