#pragma once
// Nodal block Gauss-Seidel (linalg/gauss_seidel.hpp) as a multigrid smoother: forward sweeps
// before the coarse correction, backward sweeps (their exact reverse) after it. One registration
// per ordering: sequential, multicolour, domains, hybrid (the default).
#include "linalg/gauss_seidel.hpp"
#include "linalg/smoother.hpp"

namespace corofem {

class GaussSeidelSmoother : public Smoother {
 public:
  explicit GaussSeidelSmoother(SmootherOrdering ordering)
      : ordering_(ordering), sweeps_(ordering) {}
  void set_matrix(const BrcMatrix& a) override { sweeps_.set_matrix(a); }
  /// The first forward sweep of a correction reads only the blocks below the diagonal; a single
  /// one forms its residual as it goes (the blocks it reads, transposed, are the rest of the rows
  /// above): BlockGaussSeidel::forward_from_zero_with_residual.
  bool pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, int sweeps,
                  bool zero_guess, Eigen::VectorXd& r) const override;
  bool forms_residual(int sweeps) const override { return sweeps == 1; }
  void post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   int sweeps) const override;
  Traffic setup_traffic(const BrcMatrix& a) const override;
  Traffic pre_traffic(const BrcMatrix& a, int sweeps) const override;
  Traffic post_traffic(const BrcMatrix& a, int sweeps) const override;
  Parameters describe() const override;

 private:
  SmootherOrdering ordering_;
  BlockGaussSeidel sweeps_;
};

/// The registrations of the four orderings (linalg/smoother.hpp), in kSmootherOrderings' order.
std::vector<SmootherTraits> gauss_seidel_smoothers();

}  // namespace corofem
