#include "linalg/gauss_seidel_smoother.hpp"

#include <algorithm>

namespace corofem {
namespace {

/// One sweep: per row r = b - sum A x, x += D^-1 r (the inverse diagonal blocks and their
/// positions read besides the matrix).
Traffic sweep_traffic(const BrcMatrix& a) {
  const double n = 3.0 * a.block_rows;
  return {matrix_bytes(a) + (kBlockBytes + kIndexBytes) * a.block_rows + 8 * n + 16 * n,
          18.0 * static_cast<double>(a.col_index.size()) + 21.0 * a.block_rows};
}

/// The first forward sweep of a correction, from x = 0: only the blocks below the diagonal, b
/// read, x written.
Traffic sweep_from_zero_traffic(const BrcMatrix& a, double lower) {
  const double n = 3.0 * a.block_rows;
  return {(kBlockBytes + kIndexBytes) * lower + kIndexBytes * (a.block_rows + 1) +
              (kBlockBytes + kIndexBytes) * a.block_rows + 16 * n,
          18.0 * lower + 15.0 * a.block_rows};
}

}  // namespace

bool GaussSeidelSmoother::pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b,
                                     Eigen::VectorXd& x, int sweeps, bool zero_guess,
                                     Eigen::VectorXd& r) const {
  if (zero_guess && sweeps == 1) {
    sweeps_.forward_from_zero_with_residual(a, b, x, r);
    return true;
  }
  int s = 0;
  if (zero_guess && sweeps > 0) {
    sweeps_.forward_from_zero(a, b, x);
    ++s;
  } else if (zero_guess) {
    x.setZero(b.size());
  }
  for (; s < sweeps; ++s) sweeps_.forward(a, b, x);
  return false;
}

void GaussSeidelSmoother::post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b,
                                      Eigen::VectorXd& x, int sweeps) const {
  for (int s = 0; s < sweeps; ++s) sweeps_.backward(a, b, x);
}

Traffic GaussSeidelSmoother::setup_traffic(const BrcMatrix& a) const {
  // Each diagonal block found and inverted (about 50 flops), the inverse written; hybrid: the
  // halo rows' blocks outside their domains read for the l1 norms (18 flops a block), the norms
  // written.
  const double rows = a.block_rows;
  const double off = static_cast<double>(sweeps_.off_domain_blocks());
  const bool hybrid = ordering_ == SmootherOrdering::Hybrid;
  return {(cache_lines(kBlockBytes) + kIndexBytes + kBlockBytes + (hybrid ? 24 : 0)) * rows +
              kBlockBytes * off,
          50 * rows + 18 * off};
}

Traffic GaussSeidelSmoother::pre_traffic(const BrcMatrix& a, int sweeps) const {
  if (sweeps == 0) return {};
  const double n = 3.0 * a.block_rows, lower = blocks_below_diagonal(a);
  Traffic out = (sweeps - 1) * sweep_traffic(a);
  out += sweep_from_zero_traffic(a, lower);
  // A single sweep forms r = b - A x in the same pass: the blocks it reads, transposed, 18 flops
  // each; r written. The hybrid halo rows' blocks outside their domain, read again, are left
  // out: a floor.
  if (sweeps == 1) out += {8 * n, 18 * lower + 3 * n};
  return out;
}

Traffic GaussSeidelSmoother::post_traffic(const BrcMatrix& a, int sweeps) const {
  return sweeps * sweep_traffic(a);
}

Parameters GaussSeidelSmoother::describe() const {
  Parameters p;
  p.set("kind", std::string("block-gauss-seidel"));
  p.set("ordering", std::string(kSmootherOrderings.name(ordering_)));
  if (ordering_ == SmootherOrdering::Hybrid)
    p.set("domain_blocks", static_cast<long long>(kHybridDomainBlocks));
  if (ordering_ == SmootherOrdering::Domains)
    p.set("domain_vertices", static_cast<long long>(kDomainVertices));
  return p;
}

std::vector<SmootherTraits> gauss_seidel_smoothers() {
  std::vector<SmootherTraits> out;
  for (const auto& [ordering, name] : kSmootherOrderings.entries)
    out.push_back({.name = name, .make = [ordering = ordering](const Parameters&) {
                     return std::unique_ptr<Smoother>(new GaussSeidelSmoother(ordering));
                   }});
  return out;
}

}  // namespace corofem
