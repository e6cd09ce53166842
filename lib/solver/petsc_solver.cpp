#include "solver/petsc_solver.hpp"

#include "core/errors.hpp"

#ifdef COROFEM_HAVE_PETSC
#include <petscksp.h>

#include <cmath>

#include "solver/petsc_coarse_operators.hpp"
#include "solver/petsc_support.hpp"
#endif

namespace corofem {

#ifndef COROFEM_HAVE_PETSC

bool have_petsc() {
  return false;
}

std::unique_ptr<LinearSolver> make_petsc_solver(PetscSolverKind kind, const std::vector<Vec3>&,
                                                double, int, std::vector<Transfer>, int, bool,
                                                const RankPart*, bool) {
  throw InputError(
      std::string("analysis.solver '") + kPetscSolverKinds.name(kind) +
      "' needs PETSc, which this build of corofem does not have (install petsc-dev and "
      "libhypre-dev, as ci/setup does, and rebuild)");
}

#else

bool have_petsc() {
  return true;
}

namespace {

using petsc::check;

/// GMRES's restart length for a non-symmetric matrix: an AMG-preconditioned corotated tangent
/// converges to 1e-10 in well under this many iterations.
constexpr PetscInt kGmresRestart = 50;

/// The largest relative residual accepted from the LU fallback (a singular matrix gives more).
constexpr double kDirectResidual = 1e-6;

/// Whether this PETSc has MUMPS (Debian's does): the distributed LU of petsc-mg's coarsest level
/// and of a tangent GMRES misses.
bool have_mumps() {
  PetscBool mumps = PETSC_FALSE;
  check(PetscHasExternalPackage("mumps", &mumps), "PetscHasExternalPackage");
  return mumps == PETSC_TRUE;
}

class PetscSolver : public LinearSolver {
 public:
  PetscSolver(PetscSolverKind kind, const std::vector<Vec3>& rest, double tolerance,
              int max_iterations, std::vector<Transfer> transfers, int smoothing, bool setup_reuse,
              const RankPart* part, bool nonsymmetric)
      : kind_(kind),
        name_(kPetscSolverKinds.name(kind)),
        rest_(rest),
        tolerance_(tolerance),
        max_iterations_(max_iterations),
        transfers_(std::move(transfers)),
        smoothing_(smoothing),
        setup_reuse_(setup_reuse),
        part_(part),
        nonsymmetric_(nonsymmetric),
        krylov_(nonsymmetric ? "GMRES" : "CG") {
    petsc::ensure_session();
    comm_ = PETSC_COMM_WORLD;
    MPI_Comm_size(comm_, &ranks_);
  }
  ~PetscSolver() override {
    if (ksp_) KSPDestroy(&ksp_);
    if (direct_) KSPDestroy(&direct_);
    if (part_b_) VecDestroy(&part_b_);
    if (part_x_) VecDestroy(&part_x_);
  }
  std::string name() const override { return name_; }

  void set_matrix(const BrcMatrix& a) override {
    const bool first = !a_;
    if (first) create(a);
    a_->copy(a);
    check(KSPSetOperators(ksp_, a_->mat(), a_->mat()), "KSPSetOperators");
    if (coarse_) coarse_->update(a);
    if (coarse_ && first) {
      // petsc-mg: the coarse levels' operators (made by the first update, the same matrices
      // after), PETSc level l our level L - 1 - l.
      const PetscInt levels = coarse_->coarse_levels() + 1;
      for (PetscInt l = 0; l + 1 < levels; ++l) {
        KSP smoother = nullptr;
        check(PCMGGetSmoother(pc_, l, &smoother), "PCMGGetSmoother");
        const Mat m = coarse_->level(static_cast<int>(levels - 1 - l));
        check(KSPSetOperators(smoother, m, m), "KSPSetOperators");
      }
    }
    check(KSPSetUp(ksp_), "KSPSetUp");
    check(PCSetUp(pc_), "PCSetUp");  // the AMG hierarchy: timed with the update, not the solve
    // BoomerAMG's reuse: the hierarchy of this first matrix preconditions every later solve.
    if (setup_reuse_ && kind_ == PetscSolverKind::BoomerAmg)
      check(KSPSetReusePreconditioner(ksp_, PETSC_TRUE), "KSPSetReusePreconditioner");
  }

  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (part_) return solve_part(b, x);
    SolveStats stats;
    const double b_norm = start_iterative_solve(b, x);
    if (b_norm == 0) return stats;
    // This rank's share of b and x, in place; then every rank gets the whole x back (each goes
    // on with the same step).
    const petsc::OwnedBlocks& own = a_->rows();
    const PetscInt n = static_cast<PetscInt>(b.size()), local = 3 * own.size();
    Vec vb, vx;
    check(VecCreateMPIWithArray(comm_, 3, local, n, b.data() + 3 * own.begin, &vb),
          "VecCreateMPIWithArray");
    check(VecCreateMPIWithArray(comm_, 3, local, n, x.data() + 3 * own.begin, &vx),
          "VecCreateMPIWithArray");
    const PetscErrorCode solved = KSPSolve(ksp_, vb, vx);
    const SolveStats direct = solved == 0 ? solve_directly_if_missed(vb, vx, b_norm) : SolveStats{};
    VecDestroy(&vb);
    VecDestroy(&vx);
    check(solved, "KSPSolve");
    gather(x);
    return direct.iterations > 0 ? direct : finish(stats, b_norm);
  }

 private:
  /// The solve's statistics from KSP; throws where PETSc's Krylov method failed or did not
  /// converge.
  SolveStats finish(SolveStats stats, double b_norm) const {
    PetscInt iterations = 0;
    KSPConvergedReason reason;
    PetscReal residual = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    check(KSPGetResidualNorm(ksp_, &residual), "KSPGetResidualNorm");
    stats.iterations = static_cast<int>(iterations);
    stats.residual = residual / b_norm;
    if (!std::isfinite(stats.residual))
      throw NumericalFault(name_ + ": residual became non-finite");
    if (reason < 0 && reason != KSP_DIVERGED_ITS)
      throw NumericalFault(name_ + ": PETSc's " + krylov_ + " stopped (KSPConvergedReason " +
                           std::to_string(reason) + ")");
    require_converged(stats, tolerance_, name_, krylov_ + " iterations");
    return stats;
  }

  /// Whether the last Krylov solve reached the tolerance.
  bool krylov_converged(double b_norm) const {
    KSPConvergedReason reason;
    PetscReal residual = 0;
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    check(KSPGetResidualNorm(ksp_, &residual), "KSPGetResidualNorm");
    return reason > 0 && residual <= tolerance_ * b_norm;
  }

  /// A non-symmetric matrix that GMRES did not solve (a tangent past a buckling point is
  /// indefinite, and AMG then preconditions it badly) by MUMPS's distributed LU from x = 0, as one
  /// process falls back from GMRES to UMFPACK (integrate/newton_iteration.hpp). Returns the
  /// solve's statistics (iterations: GMRES's plus one), or none (iterations 0) where GMRES had
  /// converged or this solver is CG's.
  SolveStats solve_directly_if_missed(Vec b, Vec x, double b_norm) {
    if (!nonsymmetric_ || krylov_converged(b_norm)) return {};
    if (!have_mumps()) return {};  // finish() then says that GMRES missed
    if (!direct_) {
      check(KSPCreate(comm_, &direct_), "KSPCreate");
      check(KSPSetType(direct_, KSPPREONLY), "KSPSetType");
      PC lu = nullptr;
      check(KSPGetPC(direct_, &lu), "KSPGetPC");
      check(PCSetType(lu, PCLU), "PCSetType");
      check(PCFactorSetMatSolverType(lu, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    }
    check(KSPSetOperators(direct_, a_->mat(), a_->mat()), "KSPSetOperators");
    PetscInt krylov_iterations = 0;
    check(KSPGetIterationNumber(ksp_, &krylov_iterations), "KSPGetIterationNumber");
    check(VecSet(x, 0.0), "VecSet");
    check(KSPSolve(direct_, b, x), "KSPSolve");
    Vec r;  // |b - A x|: preonly reports no residual of its own
    check(VecDuplicate(b, &r), "VecDuplicate");
    check(MatMult(a_->mat(), x, r), "MatMult");
    check(VecAYPX(r, -1.0, b), "VecAYPX");
    PetscReal residual = 0;
    check(VecNorm(r, NORM_2, &residual), "VecNorm");
    VecDestroy(&r);
    SolveStats stats{static_cast<int>(krylov_iterations) + 1, residual / b_norm, 0.0};
    if (!std::isfinite(stats.residual) || stats.residual > kDirectResidual)
      throw NumericalFault(name_ +
                           ": neither GMRES nor MUMPS's LU solved the matrix (relative "
                           "residual " +
                           std::to_string(stats.residual) + ")");
    return stats;
  }

  /// Distributed: b's and x's owned rows into PETSc's vectors (x with its halo as ghosts), the
  /// solve, and x's owned and halo entries back.
  SolveStats solve_part(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    const PetscInt local = 3 * part_->owned_vertices;
    if (x.size() != b.size()) x.setZero(b.size());
    if (!part_b_) {
      const PetscInt n = 3 * static_cast<PetscInt>(part_->global_vertices);
      check(VecCreateMPI(comm_, local, n, &part_b_), "VecCreateMPI");
      check(VecSetBlockSize(part_b_, 3), "VecSetBlockSize");
      std::vector<PetscInt> ghosts(part_->global_vertex.begin() + part_->owned_vertices,
                                   part_->global_vertex.end());
      check(VecCreateGhostBlock(comm_, 3, local, n, static_cast<PetscInt>(ghosts.size()),
                                ghosts.data(), &part_x_),
            "VecCreateGhostBlock");
    }
    PetscScalar* v = nullptr;
    check(VecGetArray(part_b_, &v), "VecGetArray");
    std::copy(b.data(), b.data() + local, v);
    check(VecRestoreArray(part_b_, &v), "VecRestoreArray");
    PetscReal b_norm = 0;
    check(VecNorm(part_b_, NORM_2, &b_norm), "VecNorm");  // over the owned rows of every rank
    if (b_norm == 0) {
      x.setZero();
      return {};
    }
    check(VecGetArray(part_x_, &v), "VecGetArray");
    std::copy(x.data(), x.data() + local, v);
    check(VecRestoreArray(part_x_, &v), "VecRestoreArray");
    check(KSPSolve(ksp_, part_b_, part_x_), "KSPSolve");
    const SolveStats direct = solve_directly_if_missed(part_b_, part_x_, b_norm);
    check(VecGhostUpdateBegin(part_x_, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
    check(VecGhostUpdateEnd(part_x_, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
    Vec with_ghosts;
    check(VecGhostGetLocalForm(part_x_, &with_ghosts), "VecGhostGetLocalForm");
    const PetscScalar* all = nullptr;
    check(VecGetArrayRead(with_ghosts, &all), "VecGetArrayRead");
    std::copy(all, all + x.size(), x.data());
    check(VecRestoreArrayRead(with_ghosts, &all), "VecRestoreArrayRead");
    check(VecGhostRestoreLocalForm(part_x_, &with_ghosts), "VecGhostRestoreLocalForm");
    return direct.iterations > 0 ? direct : finish({}, b_norm);
  }

  /// x (whole on every rank, this rank's share solved) made whole everywhere: the ranks' shares
  /// are contiguous and in rank order.
  void gather(Eigen::VectorXd& x) const {
    if (ranks_ == 1) return;
    std::vector<int> counts(ranks_), starts(ranks_);
    for (int r = 0; r < ranks_; ++r) {
      starts[r] = static_cast<int>(3 * petsc::share_start(a_->rows().count, r, ranks_));
      counts[r] =
          static_cast<int>(3 * petsc::share_start(a_->rows().count, r + 1, ranks_)) - starts[r];
    }
    if (MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, x.data(), counts.data(), starts.data(),
                       MPI_DOUBLE, comm_) != MPI_SUCCESS)
      throw NumericalFault(name_ + ": MPI_Allgatherv of the solution failed");
  }

  /// The AIJ matrix of the BRC pattern; the near null space; the Krylov method and the AMG.
  void create(const BrcMatrix& a) {
    a_ = std::make_unique<petsc::AijFromBrc>(a, comm_, part_);
    if (!nonsymmetric_) check(MatSetOption(a_->mat(), MAT_SPD, PETSC_TRUE), "MatSetOption");
    set_rigid_body_modes();
    create_krylov();
    check(KSPGetPC(ksp_, &pc_), "KSPGetPC");
    const PetscOptionDefaults option(options_prefix());
    check(KSPSetOptionsPrefix(ksp_, option.prefix.c_str()), "KSPSetOptionsPrefix");
    switch (kind_) {
      case PetscSolverKind::Mg:
        set_up_mg(a, option);
        break;
      case PetscSolverKind::Gamg:
        set_up_gamg(option);
        break;
      case PetscSolverKind::BoomerAmg:
        set_up_boomeramg(option);
        break;
    }
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  }

  /// The options database's prefix of this solver's PETSc objects.
  std::string options_prefix() const {
    return kind_ == PetscSolverKind::Gamg ? "corofem_gamg_"
           : kind_ == PetscSolverKind::Mg ? "corofem_mg_"
                                          : "corofem_boomeramg_";
  }

  /// Our defaults in PETSc's options database, under a prefix: the user's PETSC_OPTIONS win.
  struct PetscOptionDefaults {
    std::string prefix;
    void operator()(const std::string& key, const char* value) const {
      PetscBool set = PETSC_FALSE;
      check(PetscOptionsHasName(nullptr, prefix.c_str(), key.c_str(), &set), "PetscOptionsHasName");
      if (!set)
        check(PetscOptionsSetValue(nullptr, ("-" + prefix + key.substr(1)).c_str(), value),
              "PetscOptionsSetValue");
    }
  };

  /// The near null space: the rigid-body modes of the rest positions (three translations, three
  /// rotations).
  void set_rigid_body_modes() {
    const petsc::OwnedBlocks& own = a_->rows();
    Vec coordinates;
    check(VecCreateMPI(comm_, 3 * own.size(), PETSC_DETERMINE, &coordinates), "VecCreateMPI");
    check(VecSetBlockSize(coordinates, 3), "VecSetBlockSize");
    PetscScalar* x = nullptr;
    check(VecGetArray(coordinates, &x), "VecGetArray");
    const PetscInt first = part_ ? 0 : own.begin;  // a part's owned vertices come first
    for (PetscInt v = 0; v < own.size(); ++v)
      for (int c = 0; c < 3; ++c) x[3 * v + c] = rest_[first + v][c];
    check(VecRestoreArray(coordinates, &x), "VecRestoreArray");
    MatNullSpace rigid;
    check(MatNullSpaceCreateRigidBody(coordinates, &rigid), "MatNullSpaceCreateRigidBody");
    check(MatSetNearNullSpace(a_->mat(), rigid), "MatSetNearNullSpace");
    MatNullSpaceDestroy(&rigid);
    VecDestroy(&coordinates);
  }

  /// CG, or for a corotated tangent GMRES, to |b - A x| <= tolerance |b| from the given guess.
  void create_krylov() {
    check(KSPCreate(comm_, &ksp_), "KSPCreate");
    if (nonsymmetric_) {
      // GMRES preconditioned from the right, so that its norm is |b - A x| too; restarted after
      // kGmresRestart vectors (a rank's memory: that many vectors of its rows).
      check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
      check(KSPGMRESSetRestart(ksp_, kGmresRestart), "KSPGMRESSetRestart");
      check(KSPSetPCSide(ksp_, PC_RIGHT), "KSPSetPCSide");
    } else {
      check(KSPSetType(ksp_, KSPCG), "KSPSetType");
    }
    check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");  // |b - A x|, as ours
    check(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE), "KSPSetInitialGuessNonzero");
    check(KSPSetTolerances(ksp_, tolerance_, 0.0, 1e10, max_iterations_), "KSPSetTolerances");
  }

  /// PCMG on our hierarchy: our transfers as interpolations, our coarse operators.
  void set_up_mg(const BrcMatrix& a, const PetscOptionDefaults& option) {
    const petsc::OwnedBlocks& own = a_->rows();
    // PETSc numbers the levels from the coarsest (0); ours from the finest. Level l's
    // interpolation brings PETSc level l - 1 to l: our transfer L - 1 - l, P = R^T.
    const PetscInt levels = static_cast<PetscInt>(transfers_.size()) + 1;
    check(PCSetType(pc_, PCMG), "PCSetType");
    check(PCMGSetLevels(pc_, levels, nullptr), "PCMGSetLevels");
    check(PCMGSetType(pc_, PC_MG_MULTIPLICATIVE), "PCMGSetType");
    check(PCMGSetCycleType(pc_, PC_MG_CYCLE_V), "PCMGSetCycleType");
    // The coarse operators are ours (petsc_coarse_operators.hpp): the first from each rank's
    // Galerkin share of its rows, the coarser by MatPtAP; PCMG's Galerkin (MatPtAP from the
    // finest level) kept too much memory on several ranks.
    check(PCMGSetGalerkin(pc_, PC_MG_GALERKIN_NONE), "PCMGSetGalerkin");
    std::vector<Mat> prolongations;  // finest first
    for (PetscInt l = levels - 1; l >= 1; --l) {
      // The finest interpolation's rows are the matrix's (a distributed mesh's part's).
      Mat p = petsc::prolongation(transfers_[levels - 1 - l], comm_,
                                  l == levels - 1 ? &a_->rows() : nullptr);
      check(PCMGSetInterpolation(pc_, l, p), "PCMGSetInterpolation");
      prolongations.push_back(p);
    }
    // This rank's rows of the fine matrix: a part's owned rows come first; replicated, the
    // matrix and the finest transfer are whole and the rank's rows its share of them.
    const int begin = part_ ? 0 : static_cast<int>(own.begin);
    if (!transfers_.empty())  // one level (asked for, or a mesh too small to coarsen): LU
      coarse_ = std::make_unique<petsc::CoarseOperators>(
          a, transfers_[0], begin, begin + static_cast<int>(own.size()), prolongations, comm_);
    for (Mat& p : prolongations) MatDestroy(&p);  // PCMG and the operators keep references
    transfers_ = {};  // PETSc and the operators hold this rank's rows of them now
    // Level smoothers: Chebyshev (PETSc's default, eigenvalue bounds estimated at setup) on
    // point Jacobi, degree 2 per `smoothing`. With PETSc's SOR instead, as Richardson steps at
    // omega 1 or under Chebyshev, CG stopped on the gates' heterogeneous cube (indefinite
    // preconditioner; NaN).
    const std::string degree = std::to_string(2 * smoothing_);
    option("-mg_levels_ksp_type", "chebyshev");
    option("-mg_levels_ksp_max_it", degree.c_str());
    option("-mg_levels_pc_type", "jacobi");
    option("-mg_coarse_ksp_type", "preonly");
    if (ranks_ == 1) {
      option("-mg_coarse_pc_type", "lu");
    } else if (have_mumps()) {
      // MUMPS's LU is distributed: less memory a rank than PETSc's redundant LU, and as many
      // iterations.
      option("-mg_coarse_pc_type", "lu");
      option("-mg_coarse_pc_factor_mat_solver_type", "mumps");
    } else {  // PETSc's own LU is serial: each rank factors the whole coarsest matrix
      option("-mg_coarse_pc_type", "redundant");
      option("-mg_coarse_redundant_pc_type", "lu");
    }
  }

  /// PETSc's smoothed aggregation.
  void set_up_gamg(const PetscOptionDefaults& option) {
    check(PCSetType(pc_, PCGAMG), "PCSetType");
    option("-pc_gamg_type", "agg");
    option("-pc_gamg_agg_nsmooths", "1");
    option("-pc_gamg_threshold", "0.01");
    if (setup_reuse_) option("-pc_gamg_reuse_interpolation", "true");
  }

  /// hypre's BoomerAMG as systems AMG.
  void set_up_boomeramg(const PetscOptionDefaults& option) {
    check(PCSetType(pc_, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc_, "boomeramg"), "PCHYPRESetType");
    // Systems AMG by the unknown approach (PETSc passes the block size 3 as the number of
    // functions) with the strong threshold hypre's manual gives for 3D. The manual's other
    // elasticity options (nodal coarsening, the rigid-body modes in the interpolation) cost more
    // than they saved on the quadruped (lib/docs/mpi.md); PETSC_OPTIONS switches them on.
    option("-pc_hypre_boomeramg_strong_threshold", "0.5");
  }

  PetscSolverKind kind_;
  std::string name_;
  MPI_Comm comm_ = MPI_COMM_NULL;  ///< PETSC_COMM_WORLD: one rank, or the ranks of mpirun
                                   ///< (solver/mpi_launch.hpp)
  int ranks_ = 1;
  std::vector<Vec3> rest_;
  double tolerance_;
  int max_iterations_;
  std::vector<Transfer> transfers_;  ///< petsc-mg: our hierarchy, finest first
  int smoothing_;
  bool setup_reuse_;
  const RankPart* part_;                     ///< distributed: this rank's part; null: replicated
  bool nonsymmetric_;                        ///< GMRES instead of CG (a corotated tangent)
  std::string krylov_;                       ///< "CG" or "GMRES", for messages
  Vec part_b_ = nullptr, part_x_ = nullptr;  ///< distributed: b, and x with the halo as ghosts
  std::unique_ptr<petsc::AijFromBrc> a_;
  std::unique_ptr<petsc::CoarseOperators> coarse_;  ///< petsc-mg: the coarse levels' operators
  KSP ksp_ = nullptr;
  PC pc_ = nullptr;
  KSP direct_ = nullptr;  ///< non-symmetric: MUMPS's LU where GMRES misses, made at first need
};

}  // namespace

std::unique_ptr<LinearSolver> make_petsc_solver(PetscSolverKind kind,
                                                const std::vector<Vec3>& rest_positions,
                                                double tolerance, int max_iterations,
                                                std::vector<Transfer> transfers, int smoothing,
                                                bool setup_reuse, const RankPart* part,
                                                bool nonsymmetric) {
  return std::make_unique<PetscSolver>(kind, rest_positions, tolerance, max_iterations,
                                       std::move(transfers), smoothing, setup_reuse, part,
                                       nonsymmetric);
}

#endif

}  // namespace corofem
