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
  s.transpose_prolongation(begin, end);
  return s;
}

}  // namespace

GalerkinRowShare::GalerkinRowShare(const BrcMatrix& a, const Transfer& t, int begin, int end)
    : t_(share_transfer(t, begin, end)), reuse_(t.coarse) {
  if (a.block_rows + 1 > static_cast<int>(t.p_start.size()) ||
      a.block_cols + 1 > static_cast<int>(t.p_start.size()))
    throw NumericalFault("Galerkin row share: the transfer lacks rows of the matrix's vertices");
  e_ = galerkin_pattern(a, t_);
}

void GalerkinRowShare::apply(const BrcMatrix& a) {
  reuse_.apply(a, t_, e_);
}

}  // namespace corofem
