// The consistent tangent d f_int / d x of every rotation method against central finite
// differences of the force itself (re-extracting the rotations at every perturbed state), on a
// box bent, stretched and turned far from its rest shape. Also: polar's tangent is symmetric (its
// force is conservative), the energy methods' and qr's are not.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

#include "fem/corotated_assembly.hpp"
#include "fem/fe_problem.hpp"
#include "fem/rotation_tangent.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/rotation_extractor.hpp"
#include "sparse/brc_to_eigen.hpp"

namespace corofem {
namespace {

FeProblem bent_box_problem() {
  TetMesh mesh = make_box_mesh({1.0, 0.4, 0.3}, {3, 2, 2});
  std::vector<Material> m(mesh.tets.size(), Material{1e5, 0.35, 1000});
  return make_fe_problem(std::move(mesh), std::move(m));
}

/// A large smooth deformation: bend about y, stretch 1.4x along x, twist, then a rigid turn; plus
/// a small irregular part so that no two elements share a deformation gradient.
Eigen::VectorXd large_displacement(const FeProblem& p) {
  const Mat3 turn = Eigen::AngleAxisd(0.9, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd u(p.num_dofs());
  for (int v = 0; v < p.mesh.num_vertices(); ++v) {
    const Vec3 x = p.mesh.rest[v];
    const double bend = 0.8 * x.x(), twist = 0.6 * x.x();
    Vec3 y(1.4 * std::sin(bend) / 0.8 * (1 + 0.3 * x.z()), x.y(),
           x.z() + (1 - std::cos(bend)) / 0.8);
    y = Eigen::AngleAxisd(twist, Vec3::UnitX()).toRotationMatrix() * y;
    y += 0.02 * Vec3(std::sin(7.1 * v), std::cos(3.3 * v), std::sin(1.7 * v + 0.4));
    u.segment<3>(3 * v) = turn * y - x;
  }
  return u;
}

Eigen::VectorXd force_at(const FeProblem& p, RotationExtractor& method,
                         const std::vector<Mat3>& warm, const Eigen::VectorXd& u) {
  std::vector<Mat3> r = warm;
  method.extract(p.positions(u), r);
  return internal_forces(p, r, u);
}

struct Measured {
  double fd_error;      ///< |J - J_fd|_F / |J_fd|_F
  double asymmetry;     ///< |J - J^T|_F / |J|_F
  double ktilde_error;  ///< |Ktilde - J_fd|_F / |J_fd|_F: the paper's tangent, Q held constant
};

Measured measure(const std::string& name) {
  FeProblem p = bent_box_problem();
  Parameters params;  // the iterative methods converged well below the differences' size
  params.set("newton_tolerance", 1e-15);
  params.set("newton_max_iterations", 100LL);
  params.set("mueller_tolerance", 1e-15);
  params.set("mueller_iterations", 200LL);
  auto method = make_rotation_extractor(rotation_method_named(name), p.mesh, params);
  const Eigen::VectorXd u = large_displacement(p);
  std::vector<Mat3> r(p.mesh.tets.size(), Mat3::Identity());
  for (int pass = 0; pass < 3; ++pass) method->extract(p.positions(u), r);  // warm starts settle
  const RotationTangent tangent(p, rotation_method_named(name));
  BrcMatrix j = p.stiffness;
  tangent.assemble(p.positions(u), r, j);
  const Eigen::MatrixXd analytic = Eigen::MatrixXd(to_eigen(j));
  // Central differences, step 1e-6 of the unit size: truncation ~1e-12, rounding ~1e-10 relative.
  const double h = 1e-6;
  Eigen::MatrixXd fd(p.num_dofs(), p.num_dofs());
  for (int k = 0; k < p.num_dofs(); ++k) {
    Eigen::VectorXd up = u, down = u;
    up[k] += h;
    down[k] -= h;
    fd.col(k) = (force_at(p, *method, r, up) - force_at(p, *method, r, down)) / (2 * h);
  }
  Eigen::VectorXd force;
  assemble_corotated(p.elements, p.mesh, p.assembly, r, u, p.stiffness, force);
  const Eigen::MatrixXd ktilde = Eigen::MatrixXd(to_eigen(p.stiffness));
  return {(analytic - fd).norm() / fd.norm(),
          (analytic - analytic.transpose()).norm() / analytic.norm(),
          (ktilde - fd).norm() / fd.norm()};
}

/// A method and whether its force is conservative (the gradient of an energy, so its tangent
/// is symmetric): polar's rotation is the one of F, and mueller2016 and polar-fixed converge to
/// it on uninverted elements; the energy methods, qr and polar-smoothed rotate by something else.
struct TangentCase {
  const char* method;
  bool conservative;
};

void PrintTo(const TangentCase& c, std::ostream* os) {
  *os << c.method;
}

class ConsistentTangent : public ::testing::TestWithParam<TangentCase> {};

TEST_P(ConsistentTangent, EqualsFiniteDifferencesOfTheForce) {
  const std::string name = GetParam().method;
  const Measured m = measure(name);
  FeProblem p = bent_box_problem();
  const auto record = [](const char* key, double value) {
    std::ostringstream text;
    text << value;
    RecordProperty(key, text.str());
  };
  record("fd_error", m.fd_error);
  record("asymmetry", m.asymmetry);
  record("ktilde_error", m.ktilde_error);
  // On this deformation the rotation's terms are a visible part of the tangent: Ktilde alone
  // (Q held constant) is at least 1e-2 from it (4.5e-2 to 8.8e-2 measured), 1e4 times the
  // tolerance below, so that check sees a missing or wrong term.
  if (name != "none") {
    EXPECT_GT(m.ktilde_error, 1e-2)
        << name << ": the deformation no longer tests the rotation's terms";
  }
  if (RotationTangent(p, rotation_method_named(name)).exact()) {
    // The differences' truncation (~1e-12) and rounding (~1e-10) bound what they can resolve.
    EXPECT_LT(m.fd_error, 1e-6) << name;
  } else {
    // polar-smoothed: polar's rotation terms at the smoothed rotation, the dependence of the
    // smoothing on the 1-ring left out (it reaches outside K's pattern). Measured 0.17 from the
    // differences, farther than Ktilde (0.045) in this norm, yet Newton converges on it and
    // stalls on Ktilde (StaticNewton: 8.2 iterations per increment; Ktilde stops at 1e-9). So
    // this norm cannot judge its rotation terms (with their sign flipped: 0.18); what it can:
    // not exact, within 0.3 of the derivative (a tangent missing its material part or scaled
    // wrong is ~1 away), and with the rotation's non-symmetric terms present (the asymmetry
    // check below: Ktilde alone is symmetric).
    EXPECT_GT(m.fd_error, 1e-6) << name << " is exact after all: make exact() say so";
    EXPECT_LT(m.fd_error, 0.3) << name;
  }
  if (GetParam().conservative) {
    // A gradient's Jacobian is symmetric; only the sums' rounding (|J| ~ 1e5, ulps ~ 1e-16) is
    // left.
    EXPECT_LT(m.asymmetry, 1e-12) << name;
  } else {
    // No potential: an asymmetry of the size of the rotation's terms, not of rounding.
    EXPECT_GT(m.asymmetry, 1e-2) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Methods, ConsistentTangent,
    ::testing::Values(TangentCase{"polar", true}, TangentCase{"polar-fixed", true},
                      TangentCase{"mueller2016", true}, TangentCase{"polar-smoothed", false},
                      TangentCase{"energy-newton", false}, TangentCase{"energy-exact", false},
                      TangentCase{"qr", false}, TangentCase{"none", true}),
    [](const auto& info) {
      std::string s = info.param.method;
      for (char& c : s)
        if (c == '-') c = '_';
      return s;
    });

TEST(ConsistentTangent, PolarIsConservativeTheEnergyMinimizerIsNot) {
  // Polar's force is the gradient of the corotated energy: its tangent is symmetric to rounding.
  EXPECT_LT(measure("polar").asymmetry, 1e-10);
  // The energy minimizer rotates F C, not F: its force has no potential on distorted elements.
  EXPECT_GT(measure("energy-exact").asymmetry, 1e-4);
  EXPECT_GT(measure("qr").asymmetry, 1e-4);
}

TEST(ConsistentTangent, RotationFactorDerivativeOfAKnownPath) {
  // L(t) = R(t) U with R(t) = exp(t [w]x) R0 and U fixed SPD: dQ/dt = [w]x R0 exactly.
  const Mat3 r0 = Eigen::AngleAxisd(0.7, Vec3(0.2, -1, 0.5).normalized()).toRotationMatrix();
  Mat3 u;
  u << 2.0, 0.3, 0.1, 0.3, 1.5, -0.2, 0.1, -0.2, 0.8;
  const Vec3 w(0.3, -0.4, 0.9);
  Mat3 wx;
  wx << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  const Mat3 dq = rotation_factor_derivative(r0, r0 * u, wx * r0 * u);
  EXPECT_LT((dq - wx * r0).norm(), 1e-14 * wx.norm());
}

}  // namespace
}  // namespace corofem
