#include "fem/rank_view.hpp"

#include <cmath>

#include "fem/corotated_system.hpp"

namespace corofem {

double RankView::free_norm(const DirichletConditions& bc, const Eigen::VectorXd& v) const {
  if (!distributed()) return corofem::free_norm(bc, v);
  double squares = 0;
  for (int i = 0; i < 3 * owned_vertices; ++i)
    if (!bc.fixed[i]) squares += v[i] * v[i];
  return std::sqrt(sum(squares));
}

int RankView::count_inverted(const FeProblem& problem, const std::vector<Vec3>& positions) const {
  if (!distributed()) return corofem::count_inverted(problem, positions);
  const int mine = corofem::count_inverted(problem, positions, &owned_tet);
  return static_cast<int>(std::lround(sum(mine)));
}

}  // namespace corofem
