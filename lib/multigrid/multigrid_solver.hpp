#pragma once
// Geometric multigrid with Galerkin coarse operators (paper section 4; Georgii and Westermann
// 2005): V-cycles with block Gauss-Seidel smoothing and CHOLMOD on the coarsest level, as a
// solver ("multigrid") or as the preconditioner of CG ("mgpcg").
#include <nlohmann/json.hpp>

#include "multigrid/gauss_seidel.hpp"
#include "multigrid/hierarchy.hpp"
#include "solver/linear_solver.hpp"

namespace corofem {

struct MultigridParams {
  int levels = 3;                  ///< including the fine level
  int pre_smoothing = 1;           ///< forward Gauss-Seidel sweeps before the coarse correction
  int post_smoothing = 1;          ///< backward sweeps after it
  int vcycles = 0;                 ///< multigrid: fixed count; 0 = iterate to the tolerance
  int max_iterations = 500;        ///< cap on V-cycles / CG iterations
  double tolerance = 1e-8;         ///< relative residual |b - A x| / |b|
  double first_cell_factor = 1.5;  ///< level-1 lattice cell = factor x mean fine edge length
  GalerkinMethod galerkin = GalerkinMethod::Stream;

  nlohmann::json to_json() const;
};

class MultigridSolver : public LinearSolver {
 public:
  /// `fixed` per fine vertex (fully supported vertices; their rows are identity in A).
  MultigridSolver(const BrcMatrix& pattern, const std::vector<Vec3>& points,
                  const std::vector<char>& fixed, double mean_edge, const MultigridParams& params,
                  bool as_preconditioner);
  ~MultigridSolver() override;

  std::string name() const override { return preconditioner_ ? "mgpcg" : "multigrid"; }
  void set_matrix(const BrcMatrix& a) override;
  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;

  /// One V-cycle from level h for A_h x = b (x is the initial guess on entry).
  void vcycle(int h, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  const MultigridHierarchy& hierarchy() const { return hierarchy_; }
  /// How many coarsest-level factorizations needed the semidefinite shift (see set_matrix).
  int coarsest_shifts() const { return coarsest_shifts_; }

 private:
  MultigridParams params_;
  bool preconditioner_;
  MultigridHierarchy hierarchy_;
  std::vector<BlockGaussSeidel> smoothers_;
  struct Coarsest;
  std::unique_ptr<Coarsest> coarsest_;
  std::vector<Eigen::VectorXd> residual_, coarse_b_, coarse_x_;  // scratch per level
  int coarsest_shifts_ = 0;
};

}  // namespace corofem
