#pragma once
// How a process's problem sits in a run whose mesh is distributed over MPI ranks
// (mesh/rank_part.hpp): its first `owned_vertices` vertices are the rows it solves for, the rest
// its halo; its tets flagged in `owned_tet` are counted by it alone. Quantities over the whole body
// (a norm, a count) sum the owned parts over the ranks. Default: one rank, everything owned.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "fem/dirichlet.hpp"
#include "fem/fe_problem.hpp"

namespace corofem {

struct RankView {
  int owned_vertices = -1;                       ///< -1: every vertex (one rank)
  std::vector<char> owned_tet;                   ///< empty: every tet
  std::function<double(double)> sum_over_ranks;  ///< empty: one rank
  std::function<double(double)> max_over_ranks;  ///< empty: one rank

  bool distributed() const { return owned_vertices >= 0; }
  /// `value` summed over the ranks (itself with one rank).
  double sum(double value) const { return sum_over_ranks ? sum_over_ranks(value) : value; }
  /// The largest `value` over the ranks (itself with one rank).
  double max(double value) const { return max_over_ranks ? max_over_ranks(value) : value; }
  /// free_norm over the whole body: the owned free DOFs of every rank.
  double free_norm(const DirichletConditions& bc, const Eigen::VectorXd& v) const;
  /// count_inverted over the whole body: the owned tets of every rank.
  int count_inverted(const FeProblem& problem, const std::vector<Vec3>& positions) const;
};

}  // namespace corofem
