#include "multigrid/transfer.hpp"

#include <algorithm>
#include <cmath>

#include "core/threads.hpp"

namespace corofem {

void Transfer::transpose_prolongation() {
  transpose_prolongation(0, fine);
}

void Transfer::transpose_prolongation(int begin, int end) {
  r_start.assign(coarse + 1, 0);
  for (int k = p_start[begin]; k < p_start[end]; ++k) ++r_start[p_col[k] + 1];
  for (int i = 0; i < coarse; ++i) r_start[i + 1] += r_start[i];
  r_col.resize(r_start.back());
  r_weight.resize(r_start.back());
  std::vector<int> next(r_start.begin(), r_start.end() - 1);
  for (int l = begin; l < end; ++l)  // increasing l, so each R row comes out sorted
    for (int k = p_start[l]; k < p_start[l + 1]; ++k) {
      const int slot = next[p_col[k]]++;
      r_col[slot] = l;
      r_weight[slot] = p_weight[k];
    }
}

std::vector<int> Transfer::keep_supported_coarse_vertices(int candidates) {
  std::vector<int> renumber(candidates, -1), kept;
  for (int i : p_col) renumber[i] = 0;
  for (int i = 0; i < candidates; ++i)
    if (renumber[i] == 0) {
      renumber[i] = static_cast<int>(kept.size());
      kept.push_back(i);
    }
  for (int& i : p_col) i = renumber[i];  // monotone: rows stay sorted
  coarse = static_cast<int>(kept.size());
  transpose_prolongation();
  return kept;
}

void Transfer::restrict_to(const Eigen::VectorXd& f, Eigen::VectorXd& c) const {
  c.resize(3 * coarse);
#pragma omp parallel for schedule(static) \
    num_threads(threads_for(static_cast <long long>(r_col.size())))
  for (int i = 0; i < coarse; ++i) {
    Vec3 sum = Vec3::Zero();
    for (int k = r_start[i]; k < r_start[i + 1]; ++k)
      sum += r_weight[k] * f.segment<3>(3 * r_col[k]);
    c.segment<3>(3 * i) = sum;
  }
}

void Transfer::prolongate_add(const Eigen::VectorXd& c, Eigen::VectorXd& f) const {
#pragma omp parallel for schedule(static) \
    num_threads(threads_for(static_cast <long long>(p_col.size())))
  for (int l = 0; l < fine; ++l) {
    Vec3 sum = Vec3::Zero();
    for (int k = p_start[l]; k < p_start[l + 1]; ++k)
      sum += p_weight[k] * c.segment<3>(3 * p_col[k]);
    f.segment<3>(3 * l) += sum;
  }
}

Eigen::SparseMatrix<double> restriction_matrix(const Transfer& t) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < t.coarse; ++i)
    for (int k = t.r_start[i]; k < t.r_start[i + 1]; ++k)
      for (int c = 0; c < 3; ++c)
        triplets.emplace_back(3 * i + c, 3 * t.r_col[k] + c, t.r_weight[k]);
  Eigen::SparseMatrix<double> r(3 * t.coarse, 3 * t.fine);
  r.setFromTriplets(triplets.begin(), triplets.end());
  return r;
}

double mean_edge_length(const TetMesh& mesh) {
  double sum = 0;
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) sum += (mesh.rest[t[a]] - mesh.rest[t[b]]).norm();
  return sum / (6.0 * mesh.tets.size());
}

Transfer rows_of(const Transfer& t, const std::vector<int>& vertices) {
  Transfer slice;
  slice.coarse = t.coarse;
  slice.fine = t.fine;
  slice.first_row = vertices.empty() ? 0 : vertices.front();
  slice.p_start.reserve(vertices.size() + 1);
  slice.p_start.push_back(0);
  for (const int l : vertices) {
    const int first = t.p_start[l - t.first_row], last = t.p_start[l - t.first_row + 1];
    slice.p_col.insert(slice.p_col.end(), t.p_col.begin() + first, t.p_col.begin() + last);
    slice.p_weight.insert(slice.p_weight.end(), t.p_weight.begin() + first,
                          t.p_weight.begin() + last);
    slice.p_start.push_back(static_cast<int>(slice.p_col.size()));
  }
  return slice;
}

}  // namespace corofem
