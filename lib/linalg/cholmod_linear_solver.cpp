#include <optional>

#include "core/errors.hpp"
#include "linalg/cholmod_factorization.hpp"
#include "linalg/linear_solver.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {
namespace {

class CholmodLinearSolver : public LinearSolver {
 public:
  explicit CholmodLinearSolver(Factorization kind) : solver_(kind) {}
  std::string name() const override { return "cholmod"; }
  void set_matrix(const BrcMatrix& a) override {
    if (!converter_) {
      converter_.emplace(a);
      solver_.analyze(converter_->matrix());
    } else {
      converter_->update(a);
    }
    try {
      solver_.factorize(converter_->matrix());
    } catch (const std::runtime_error& e) {
      throw NumericalFault(std::string(e.what()) +
                           " (system matrix lost definiteness: inverted elements or no supports?)");
    }
    mark_event(events_, "factorization");
  }
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = solver_.solve(b);
    SolveStats stats;
    stats.iterations = 1;
    const double bn = b.norm();
    stats.residual = bn > 0 ? (b - converter_->matrix() * x).norm() / bn : 0.0;
    report_solved(stats);
    return stats;
  }

 private:
  std::optional<BrcToEigen> converter_;
  CholmodFactorization solver_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver(Factorization kind) {
  return std::make_unique<CholmodLinearSolver>(kind);
}

}  // namespace corofem
