// A smoother of one's own: damped l1 block Jacobi, x += w M^-1 (b - A x) with M the block
// diagonal plus each row's l1 norm outside its block (every eigenvalue of M^-1 A then lies in
// (0, 1], so any w in (0, 1] converges); the same before and after the coarse correction, so the
// V-cycle stays a symmetric preconditioner. Its damping w is a setting of its own, declared in its
// registration: a scene gives it as analysis.jacobi_damping (default 0.8), and corofem reads,
// checks and records it as it does its own smoothers'.
#include "core/types.hpp"
#include "linalg/chebyshev_smoother.hpp"
#include "own_method.hpp"

namespace own {

class DampedL1Jacobi : public corofem::Smoother {
 public:
  explicit DampedL1Jacobi(double damping) : damping_(damping) {}
  void set_matrix(const corofem::BrcMatrix& a) override {
    inverse_ = corofem::l1_block_diagonal_inverse(a);  // Chebyshev's diagonal, corofem's own
  }
  bool pre_smooth(const corofem::BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                  int sweeps, bool zero_guess, Eigen::VectorXd&) const override {
    if (zero_guess) x.setZero(b.size());
    post_smooth(a, b, x, sweeps);
    return false;
  }
  bool forms_residual(int) const override { return false; }
  void post_smooth(const corofem::BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   int sweeps) const override {
    Eigen::VectorXd r;
    for (int s = 0; s < sweeps; ++s) {
      a.residual(b, x, r);
      for (int i = 0; i < a.block_rows; ++i)
        x.segment<3>(3 * i) += damping_ * (inverse_[i] * r.segment<3>(3 * i));
    }
  }
  corofem::Traffic setup_traffic(const corofem::BrcMatrix& a) const override {
    return {corofem::matrix_bytes(a) + corofem::kBlockBytes * a.block_rows, 50.0 * a.block_rows};
  }
  corofem::Traffic pre_traffic(const corofem::BrcMatrix& a, int sweeps) const override {
    return post_traffic(a, sweeps);
  }
  corofem::Traffic post_traffic(const corofem::BrcMatrix& a, int sweeps) const override {
    // Per sweep: the residual (the matrix, x and b read, r written), then the inverse blocks and
    // r read, x updated.
    const double n = 3.0 * a.block_rows;
    return sweeps * corofem::Traffic{corofem::matrix_bytes(a) + 24 * n +
                                         corofem::kBlockBytes * a.block_rows + 24 * n,
                                     18.0 * static_cast<double>(a.col_index.size()) + 21 * n};
  }
  corofem::Parameters describe() const override {
    corofem::Parameters p;
    p.set("kind", std::string(kDampedL1Jacobi));
    p.set("damping", damping_);
    return p;
  }

 private:
  double damping_;
  std::vector<corofem::Mat3> inverse_;
};

void register_damped_l1_jacobi() {
  corofem::register_smoother(
      {.name = kDampedL1Jacobi,
       .parameters = {{.key = "jacobi_damping",
                       .kind = corofem::ParameterSpec::Kind::Number,
                       .fallback = 0.8,
                       .min = 0.05,
                       .max = 1,
                       .meaning = "damped-l1-jacobi: the damping w of x += w M^-1 (b - A x)"}},
       .make = [](const corofem::Parameters& p) {
         return std::unique_ptr<corofem::Smoother>(new DampedL1Jacobi(p.number("jacobi_damping")));
       }});
}

}  // namespace own
