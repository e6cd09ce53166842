#include "fem/dirichlet.hpp"

#include <cmath>

#include "core/threads.hpp"

namespace corofem {

DirichletConditions DirichletConditions::none(int num_dofs) {
  DirichletConditions bc;
  bc.fixed.assign(num_dofs, 0);
  bc.value = Eigen::VectorXd::Zero(num_dofs);
  return bc;
}

void DirichletConditions::fix_vertex(int v, const Eigen::Vector3d& displacement) {
  for (int c = 0; c < 3; ++c) fixed[3 * v + c] = 1;
  value.segment<3>(3 * v) = displacement;
}

int DirichletConditions::num_fixed() const {
  int n = 0;
  for (char f : fixed) n += f;
  return n;
}

void apply_dirichlet(const DirichletConditions& bc, BrcMatrix& a, Eigen::VectorXd& b) {
  // Only blocks in a row or column of a vertex with a fixed DOF change: find them from the
  // column indices (4 B a block) instead of visiting all 9 entries of every block.
  std::vector<char> vertex_fixed(a.block_rows, 0);
  for (int d = 0; d < static_cast<int>(bc.fixed.size()); ++d) vertex_fixed[d / 3] |= bc.fixed[d];
  // Each row's entries, and its b, are written by one thread, in the serial order.
#pragma omp parallel for schedule(static) num_threads(threads_for(a.block_rows / 4))
  for (int i = 0; i < a.block_rows; ++i) {
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      const int j = a.col_index[k];
      if (!vertex_fixed[i] && !vertex_fixed[j]) continue;
      double* block = a.values.data() + 9 * static_cast<std::size_t>(k);
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * i + r;
        for (int c = 0; c < 3; ++c) {
          const int col = 3 * j + c;
          double& entry = block[3 * r + c];
          if (!bc.fixed[row] && bc.fixed[col]) b[row] -= entry * bc.value[col];
          if (bc.fixed[row] || bc.fixed[col]) entry = (row == col) ? 1.0 : 0.0;
        }
      }
    }
  }
  for (int d = 0; d < static_cast<int>(bc.fixed.size()); ++d)
    if (bc.fixed[d]) b[d] = bc.value[d];
}

double free_norm(const DirichletConditions& bc, const Eigen::VectorXd& v) {
  double sum = 0;
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (!bc.fixed[d]) sum += v[d] * v[d];
  return std::sqrt(sum);
}

}  // namespace corofem
