#include "multigrid/galerkin_row_share.hpp"

#include <string>

#include "core/errors.hpp"

namespace corofem {

namespace {

/// P's rows of `t` (indexed from 0, whatever t.first_row says) with R's rows made of P's rows
/// [begin, end) only: E = R A R^T over this transfer is then the rows' share.
Transfer share_transfer(const Transfer& t, int begin, int end) {
  if (begin < 0 || begin > end || end + 1 > static_cast<int>(t.p_start.size()))
    throw NumericalFault("Galerkin row share: rows [" + std::to_string(begin) + ", " +
                         std::to_string(end) + ") are not all in the transfer's " +
                         std::to_string(t.p_start.size() - 1) + " rows");
  Transfer s;
  s.coarse = t.coarse;
  s.fine = static_cast<int>(t.p_start.size()) - 1;
  s.p_start = t.p_start;
  s.p_col = t.p_col;
  s.p_weight = t.p_weight;
  s.r_start.assign(s.coarse + 1, 0);
  for (int k = s.p_start[begin]; k < s.p_start[end]; ++k) ++s.r_start[s.p_col[k] + 1];
  for (int i = 0; i < s.coarse; ++i) s.r_start[i + 1] += s.r_start[i];
  s.r_col.resize(s.r_start.back());
  s.r_weight.resize(s.r_start.back());
  std::vector<int> next(s.r_start.begin(), s.r_start.end() - 1);
  for (int l = begin; l < end; ++l)  // increasing l: each R row comes out sorted
    for (int k = s.p_start[l]; k < s.p_start[l + 1]; ++k) {
      const int slot = next[s.p_col[k]]++;
      s.r_col[slot] = l;
      s.r_weight[slot] = s.p_weight[k];
    }
  return s;
}

}  // namespace

GalerkinRowShare::GalerkinRowShare(const BrcMatrix& a, const Transfer& t, int begin, int end)
    : t_(share_transfer(t, begin, end)), reuse_(t.coarse) {
  if (a.block_rows + 1 > static_cast<int>(t.p_start.size()) ||
      a.block_cols + 1 > static_cast<int>(t.p_start.size()))
    throw NumericalFault("Galerkin row share: the transfer lacks rows of the matrix's vertices");
  e_ = galerkin_pattern(a, t_);
  for (int i = 0; i < e_.block_rows; ++i)
    if (e_.row_start[i + 1] > e_.row_start[i]) rows_.push_back(i);
}

void GalerkinRowShare::apply(const BrcMatrix& a) {
  reuse_.apply(a, t_, e_);
}

}  // namespace corofem
