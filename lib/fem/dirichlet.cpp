#include "fem/dirichlet.hpp"

#include <cmath>

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
  for (int i = 0; i < a.block_rows; ++i) {
    for (int k = a.row_start[i]; k < a.row_start[i + 1]; ++k) {
      const int j = a.col_index[k];
      double* block = a.values.data() + 9 * k;
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
