#include "fem/rank_view.hpp"

#include <cmath>

#include "core/threads.hpp"
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
  int inverted = 0;
#pragma omp parallel for schedule(static) reduction(+ : inverted) num_threads(threads_for(problem.mesh.num_tets()))
  for (int e = 0; e < problem.mesh.num_tets(); ++e)
    if (owned_tet[e] && deformation_gradient(problem.elements[e].rest_edge_inverse(), positions,
                                             problem.mesh.tets[e])
                                .determinant() <= 0)
      ++inverted;
  return static_cast<int>(std::lround(sum(inverted)));
}

}  // namespace corofem
