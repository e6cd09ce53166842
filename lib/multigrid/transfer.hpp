#pragma once
// Transfer between two levels of a non-nested hierarchy (paper section 4): R (coarse x fine) and
// its transpose, the prolongation P = R^T, by barycentric interpolation of fine vertices in coarse
// tets. Scalar per vertex pair, applied to each of the 3 components (R = Rs (x) I3).
#include <Eigen/SparseCore>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace corofem {

struct Transfer {
  int coarse = 0, fine = 0;  ///< vertex counts
  /// Rows of P = R^T: for fine vertex l, the coarse vertices i and weights R_il (sorted by i),
  /// at p_start[l - first_row].
  std::vector<int> p_start, p_col;
  std::vector<double> p_weight;
  /// Rows of R: for coarse vertex i, the fine vertices l and weights R_il (sorted by l).
  std::vector<int> r_start, r_col;
  std::vector<double> r_weight;
  /// The first fine vertex whose row of P is held: 0 but in a rows_of slice.
  int first_row = 0;

  /// Builds R's rows from P's (call after filling p_*); from P's rows [begin, end) alone where
  /// given (R's share of those fine vertices: multigrid/galerkin_row_share.hpp).
  void transpose_prolongation();
  void transpose_prolongation(int begin, int end);
  /// Finishes a transfer whose p_col index `candidates` coarse vertices: drops those that support
  /// no fine vertex (their rows of E would be zero), renumbers the rest in their original order
  /// (so P's rows stay sorted), sets `coarse` and builds R. Returns the kept candidates' ids.
  std::vector<int> keep_supported_coarse_vertices(int candidates);
  /// x_coarse = R x_fine and x_fine += R^T x_coarse (3 components per vertex).
  void restrict_to(const Eigen::VectorXd& fine, Eigen::VectorXd& coarse) const;
  void prolongate_add(const Eigen::VectorXd& coarse, Eigen::VectorXd& fine) const;
};

/// P's rows of the fine vertices `vertices` of `t` alone, in that order (R's rows left empty):
/// what a rank of a distributed run needs of the finest transfer, `vertices` being its part's
/// (rank_part.hpp: its owned vertices, a contiguous range, then its halo). first_row =
/// vertices[0], so that the owned vertices' rows are where a contiguous slice has them; the halo's
/// follow, for the rank's Galerkin share (galerkin_row_share.hpp).
Transfer rows_of(const Transfer& t, const std::vector<int>& vertices);

/// R as a scalar sparse matrix of DOFs (3 coarse x 3 fine; R = Rs (x) I3), DOF 3 v + c.
Eigen::SparseMatrix<double> restriction_matrix(const Transfer& t);

/// One coarser level: the transfer from the level above and the coarse vertex positions.
struct CoarseLevel {
  Transfer transfer;
  std::vector<Vec3> points;
};

/// Mean edge length of the mesh (sets the first lattice's cell size).
double mean_edge_length(const TetMesh& mesh);

}  // namespace corofem
