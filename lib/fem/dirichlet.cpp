#include "fem/dirichlet.hpp"

#include <cmath>
#include <string>

#include "core/errors.hpp"

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

std::vector<char> DirichletConditions::supported_vertices() const {
  std::vector<char> supported(fixed.size() / 3, 0);
  for (std::size_t d = 0; d < fixed.size(); ++d) supported[d / 3] |= fixed[d];
  return supported;
}

namespace {

/// apply_dirichlet, with b left alone where it is null.
void constrain(const DirichletConditions& bc, BrcMatrix& a, Eigen::VectorXd* b) {
  // Only blocks in a row or column of a vertex with a fixed DOF change. The pattern is symmetric
  // (an FE matrix's), so they are row v and, through v's neighbours i, the blocks (i, v): visited
  // from the supported vertices alone, not by scanning every block's column.
  const std::vector<char> vertex_fixed = bc.supported_vertices();
  // A block visited twice is visited as no-op the second time: its entries in a fixed row or
  // column are then 0 (or 1), so b loses nothing more. Row i's b sees the fixed columns in
  // ascending order, as a scan of the row would.
  const auto apply = [&](int i, int k) {
    const int j = a.col_index[k];
    double* block = a.values.data() + 9 * static_cast<std::size_t>(k);
    for (int r = 0; r < 3; ++r) {
      const int row = 3 * i + r;
      for (int c = 0; c < 3; ++c) {
        const int col = 3 * j + c;
        double& entry = block[3 * r + c];
        if (b && !bc.fixed[row] && bc.fixed[col]) (*b)[row] -= entry * bc.value[col];
        if (bc.fixed[row] || bc.fixed[col]) entry = (row == col) ? 1.0 : 0.0;
      }
    }
  };
  for (int v = 0; v < a.block_rows; ++v) {
    if (!vertex_fixed[v]) continue;
    for (int k = a.row_start[v]; k < a.row_start[v + 1]; ++k) {
      const int i = a.col_index[k];
      apply(v, k);  // row v
      if (i == v) continue;
      const int transposed = a.find(i, v);  // column v, in row i
      if (transposed < 0)
        throw NumericalFault("supports: the matrix pattern is not symmetric (block (" +
                             std::to_string(v) + ", " + std::to_string(i) + ") without (" +
                             std::to_string(i) + ", " + std::to_string(v) + "))");
      apply(i, transposed);
    }
  }
  if (!b) return;
  for (int d = 0; d < static_cast<int>(bc.fixed.size()); ++d)
    if (bc.fixed[d]) (*b)[d] = bc.value[d];
}

}  // namespace

void apply_dirichlet(const DirichletConditions& bc, BrcMatrix& a, Eigen::VectorXd& b) {
  constrain(bc, a, &b);
}

void apply_dirichlet_to_matrix(const DirichletConditions& bc, BrcMatrix& a) {
  constrain(bc, a, nullptr);
}

double free_norm(const DirichletConditions& bc, const Eigen::VectorXd& v) {
  double sum = 0;
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (!bc.fixed[d]) sum += v[d] * v[d];
  return std::sqrt(sum);
}

}  // namespace corofem
