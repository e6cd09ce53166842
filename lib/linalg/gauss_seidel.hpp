#pragma once
// Nodal 3x3-block Gauss-Seidel: x_i <- D_ii^{-1} (b_i - sum_{j != i} A_ij x_j), vertex by vertex.
// Forward then backward sweeps make the V-cycle a symmetric preconditioner for CG.
// Four orderings, each a fixed order of the vertices whatever the thread count (so the same
// bits at every count), the backward sweep its exact reverse (so the pair stays symmetric):
//  - sequential: the vertices' own order, one thread;
//  - multicolour: vertices sharing no block get one colour and relax together on every thread;
//  - domains: the rows split into contiguous domains of about 4096 vertices (a count set by the
//    level's size, not by the threads); first every domain's interior vertices (no neighbour in
//    another domain) in their own order, the domains side by side on the threads, then the
//    vertices on domain boundaries by colours. On a locality-ordered mesh nearly every vertex is
//    interior, so this is nearly the sequential smoother, with its locality, on every thread.
//  - hybrid: l1 hybrid Gauss-Seidel (Baker, Falgout, Kolev and Yang 2011, "Multigrid smoothers
//    for ultraparallel computing", the l1-GS of hypre's BoomerAMG): the rows split into an even
//    number of contiguous domains of at most 24576 blocks, as few as that allows (a count set by
//    the level's size: some 2000 fine vertices or more, fewer on the denser Galerkin levels); each
//    domain relaxes its rows in order, Gauss-Seidel inside it and Jacobi across its boundary (the
//    other domains' values from before the sweep), its boundary rows' diagonal blocks increased
//    by the l1 norm of their off-domain entries, row by row. That makes the smoother M = D + D_l1
//    + L_domains with M + M^T - A = D + 2 D_l1 - A_off positive definite, so the V-cycle stays a
//    convergent SPD preconditioner; no colouring, so every row keeps the sequential locality.
// Their rho against each other: BM_MultigridQuality and verify/multigrid_solver_test.cpp.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/name_table.hpp"
#include "sparse/brc_matrix.hpp"

namespace corofem {

enum class SmootherOrdering { Sequential, Multicolour, Domains, Hybrid };
/// The domains' default size: vertices for the domains ordering, blocks for the hybrid one.
inline constexpr int kDomainVertices = 4096;
inline constexpr int kHybridDomainBlocks = 24576;
/// The orderings' names in scenes and records.
inline constexpr NameTable<SmootherOrdering, 4> kSmootherOrderings{
    {{{SmootherOrdering::Sequential, "sequential"},
      {SmootherOrdering::Multicolour, "multicolour"},
      {SmootherOrdering::Domains, "domains"},
      {SmootherOrdering::Hybrid, "hybrid"}}}};

class BlockGaussSeidel {
 public:
  /// `domain_size`: the domains' size, in vertices for the domains ordering (0: 4096), in blocks
  /// for the hybrid one (0: 24576).
  explicit BlockGaussSeidel(SmootherOrdering ordering = SmootherOrdering::Sequential,
                            int domain_size = 0)
      : ordering_(ordering),
        domain_size_(domain_size > 0                        ? domain_size
                     : ordering == SmootherOrdering::Hybrid ? kHybridDomainBlocks
                                                            : kDomainVertices) {}
  /// Inverts the diagonal blocks of A (recompute whenever A's values change); colours A's
  /// pattern the first time (multicolour).
  void set_matrix(const BrcMatrix& a);
  void forward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  void backward(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// x = the forward sweep from x = 0, whatever x holds on entry (a V-cycle's pre-smoothing of
  /// a correction): the same bits as x.setZero(); forward(a, b, x), reading for the sequential
  /// and hybrid orderings only the blocks below the diagonal.
  void forward_from_zero(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// forward_from_zero(a, b, x) (the same bits) and r = b - A x for the x it leaves, in one pass
  /// for the sequential and hybrid orderings: the sweep leaves b_i - (the blocks it read) x =
  /// (M_ii - A_ii) x_i, the l1 term (0 for the sequential one), and the blocks it reads,
  /// transposed, are the blocks right of the diagonal in the rows above; only the blocks outside
  /// each row's domain are read a second time. Requires A symmetric bit for bit (an FE matrix and
  /// its Galerkin products are). b - A x to round-off; the other orderings compute it in full.
  void forward_from_zero_with_residual(const BrcMatrix& a, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, Eigen::VectorXd& r) const;
  /// z = D^{-1} r with the same inverted diagonal blocks (the block-Jacobi preconditioner; with
  /// the hybrid ordering, the l1-augmented ones).
  void block_jacobi(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  int num_colours() const { return static_cast<int>(colour_start_.size()) - 1; }
  int num_domains() const { return static_cast<int>(domain_start_.size()) - 1; }
  /// Rows relaxed by colours (all of them for multicolour, the domain boundaries for domains).
  int coloured_rows() const { return static_cast<int>(colour_rows_.size()); }
  /// Hybrid: rows with a neighbour in another domain (coupled to it by Jacobi), and domain d's
  /// rows [domain_rows_begin(d), domain_rows_begin(d + 1)).
  int boundary_rows() const { return static_cast<int>(halo_rows_.size()); }
  /// Hybrid: the blocks of the halo rows outside their domains (set_matrix reads them for the
  /// l1 norms); 0 before the first set_matrix.
  long long off_domain_blocks() const { return off_domain_blocks_; }
  int domain_rows_begin(int d) const { return domain_start_[d]; }

 private:
  void sweep_colour(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    int colour) const;
  void sweep_domains(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                     bool forward) const;
  /// Relaxes row i: every column read from x, or, for the hybrid smoother, from x inside the
  /// row's domain [lo, hi) and from frozen_ outside it; Backward: its blocks in reverse order.
  template <bool Hybrid, bool Backward>
  void relax_row(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int i, int lo,
                 int hi) const;
  /// forward_from_zero, and with `r` also its residual (forward_from_zero_with_residual).
  void sweep_from_zero(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                       Eigen::VectorXd* r) const;
  /// r_i -= (the blocks outside row i's domain) x, for the hybrid halo rows; an omp for inside
  /// the caller's parallel region, after its domains.
  void subtract_off_domain_products(const BrcMatrix& a, const double* x, double* r) const;
  void sweep_hybrid(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    bool forward) const;
  void order_rows(const BrcMatrix& a);
  void order_hybrid(const BrcMatrix& a);
  SmootherOrdering ordering_;
  int domain_size_;
  bool ordered_ = false;
  std::vector<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> inverse_diagonal_;
  Eigen::VectorXd l1_;  ///< hybrid: the l1 norms added to the diagonal, 3 per row
  std::vector<int> diagonal_block_;
  std::vector<int> colour_start_, colour_rows_;  ///< rows of each colour, ascending
  std::vector<int> domain_start_, domain_rows_;  ///< interior rows of each domain, ascending
  // Hybrid: domain d is rows [domain_start_[d], domain_start_[d + 1]); row i's in-domain blocks
  // are [own_begin_[i], own_end_[i]) (columns sorted, the domain contiguous).
  std::vector<int> own_begin_, own_end_;
  long long off_domain_blocks_ = 0;
  std::vector<int> halo_rows_;  ///< hybrid: the rows with blocks outside their domain, ascending
  mutable Eigen::VectorXd frozen_;  ///< x at the start of a hybrid sweep
};

}  // namespace corofem
