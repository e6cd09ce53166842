#include "multigrid/multigrid_solver.hpp"

#include <cmath>
#include <optional>

#include "cholmod_solver.hpp"
#include "core/errors.hpp"
#include "solver/preconditioned_cg.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {

nlohmann::json MultigridParams::to_json() const {
  const char* names[] = {"naive", "stream", "stream-full", "reuse"};
  return {{"levels", levels},
          {"pre_smoothing", pre_smoothing},
          {"post_smoothing", post_smoothing},
          {"vcycles", vcycles},
          {"max_iterations", max_iterations},
          {"tolerance", tolerance},
          {"first_cell_factor", first_cell_factor},
          {"galerkin", names[static_cast<int>(galerkin)]}};
}

struct MultigridSolver::Coarsest {
  std::optional<BrcToEigen> converter;
  reference::CholmodSolver cholmod;
};

MultigridSolver::MultigridSolver(const BrcMatrix& pattern, const std::vector<Vec3>& points,
                                 const std::vector<char>& fixed, double mean_edge,
                                 const MultigridParams& params, bool as_preconditioner)
    : params_(params),
      preconditioner_(as_preconditioner),
      hierarchy_(pattern, points, fixed, params.first_cell_factor * mean_edge, params.levels),
      smoothers_(hierarchy_.num_levels()),
      coarsest_(std::make_unique<Coarsest>()),
      residual_(hierarchy_.num_levels()),
      coarse_b_(hierarchy_.num_levels()),
      coarse_x_(hierarchy_.num_levels()) {}

MultigridSolver::~MultigridSolver() = default;

void MultigridSolver::set_matrix(const BrcMatrix& a) {
  hierarchy_.update(a, params_.galerkin);
  const int last = hierarchy_.num_levels() - 1;
  for (int h = 0; h < last; ++h) smoothers_[h].set_matrix(hierarchy_.matrix(h));
  if (!coarsest_->converter) {
    coarsest_->converter.emplace(hierarchy_.matrix(last));
    coarsest_->cholmod.analyze(coarsest_->converter->matrix());
  } else {
    coarsest_->converter->update(hierarchy_.matrix(last));
  }
  // E = R A R^T is only semidefinite when lattice vertices of thin parts have linearly dependent
  // prolongation columns. Then null(E) = null(R^T): the restricted residual has no component
  // there and R^T annihilates whatever the solve puts there, so a tiny diagonal shift changes
  // the coarse correction only at the shift's relative size. Once needed, it is kept (the
  // pattern of dependence does not change with the values).
  if (coarsest_shifts_ == 0) {
    try {
      coarsest_->cholmod.factorize(coarsest_->converter->matrix());
      return;
    } catch (const std::runtime_error&) {
    }
  }
  Eigen::SparseMatrix<double> shifted = coarsest_->converter->matrix();
  const double shift = 1e-10 * shifted.diagonal().cwiseAbs().mean();
  for (int i = 0; i < shifted.rows(); ++i) shifted.coeffRef(i, i) += shift;
  try {
    coarsest_->cholmod.factorize(shifted);
    ++coarsest_shifts_;
  } catch (const std::runtime_error& e) {
    throw NumericalFault(std::string("multigrid coarsest level: ") + e.what());
  }
}

void MultigridSolver::vcycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int last = hierarchy_.num_levels() - 1;
  if (h == last) {
    x = coarsest_->cholmod.solve(b);
    return;
  }
  const BrcMatrix& a = hierarchy_.matrix(h);
  for (int s = 0; s < params_.pre_smoothing; ++s) smoothers_[h].forward(a, b, x);
  a.multiply(x, residual_[h]);
  residual_[h] = b - residual_[h];
  hierarchy_.transfer(h).restrict_to(residual_[h], coarse_b_[h + 1]);
  coarse_x_[h + 1].setZero(coarse_b_[h + 1].size());
  vcycle(h + 1, coarse_b_[h + 1], coarse_x_[h + 1]);
  hierarchy_.transfer(h).prolongate_add(coarse_x_[h + 1], x);
  for (int s = 0; s < params_.post_smoothing; ++s) smoothers_[h].backward(a, b, x);
}

SolveStats MultigridSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const BrcMatrix& a = hierarchy_.matrix(0);
  if (preconditioner_)
    return preconditioned_cg(
        a, b, x, [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { vcycle(0, r, z); },
        params_.tolerance, params_.max_iterations, "mgpcg");
  if (x.size() != b.size()) x.setZero(b.size());
  SolveStats stats;
  const double b_norm = b.norm();
  if (b_norm == 0) {
    x.setZero();
    return stats;
  }
  const double r0 = (b - a * x).norm();
  const int cap = params_.vcycles > 0 ? params_.vcycles : params_.max_iterations;
  double rk = r0;
  for (int k = 0; k < cap; ++k) {
    if (params_.vcycles == 0 && rk <= params_.tolerance * b_norm) break;
    vcycle(0, b, x);
    rk = (b - a * x).norm();
    ++stats.iterations;
    if (!std::isfinite(rk)) throw NumericalFault("multigrid: residual became non-finite");
  }
  stats.residual = rk / b_norm;
  stats.convergence_factor =
      stats.iterations > 0 && r0 > 0 ? std::pow(rk / r0, 1.0 / stats.iterations) : 0;
  return stats;
}

}  // namespace corofem
