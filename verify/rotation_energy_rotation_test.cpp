// The paper's energy minimization against exact oracles: Horn's matrix, the quadrature against
// the closed form, and Newton / closed form / SVD / Horn / brute force on a catalogue of >= 1000
// elements: regular, skinny, flat, stretched 10x, compressed to 0.1x, sheared, and inverted.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <random>

#include "exact_rotation.hpp"
#include "mesh/box_mesh.hpp"
#include "rotation/energy_newton_batch.hpp"
#include "rotation/energy_rotation.hpp"
#include "rotation/quaternion.hpp"
#include "rotation/rotation_factor.hpp"
#include "sparse/block_kernels.hpp"

namespace corofem {
namespace {

using reference::brute_force_minimize;
using reference::rotation_factor_horn;
using reference::rotation_factor_svd;

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

/// One test element: rest vertices and a deformation gradient.
struct Case {
  std::array<Vec3, 4> rest;
  Mat3 f;
  std::string kind;
};

std::vector<Case> catalogue(int per_kind, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), pos(0.2, 1);
  std::vector<Case> cases;
  const char* kinds[] = {"regular",    "skinny",  "flat",     "stretched",
                         "compressed", "sheared", "inverted", "inverted-symmetric"};
  for (const char* kind : kinds) {
    for (int i = 0; i < per_kind; ++i) {
      Case c;
      c.kind = kind;
      // Rest shape: regular tet, or a needle / sliver by scaling one or two axes.
      std::array<Vec3, 4> base{Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
      Vec3 shape(1, 1, 1);
      if (c.kind == "skinny") shape = Vec3(1, 0.05, 0.05);
      if (c.kind == "flat") shape = Vec3(1, 1, 0.02);
      const Mat3 orient = random_rotation(rng);
      // The symmetric inverted kind keeps the exact regular tet (isotropic C), so that two
      // singular values of S = F C tie and the minimizer is a whole circle of rotations.
      const double noise = c.kind == "inverted-symmetric" ? 0.0 : 0.2;
      for (int a = 0; a < 4; ++a)
        c.rest[a] = orient * shape.cwiseProduct(base[a] + noise * Vec3(u(rng), u(rng), u(rng)));
      if (signed_volume(c.rest[0], c.rest[1], c.rest[2], c.rest[3]) < 0)
        std::swap(c.rest[2], c.rest[3]);
      // Deformation: a random rotation times a stretch of the requested kind.
      const Mat3 r = random_rotation(rng), v = random_rotation(rng);
      Vec3 stretch(pos(rng) + 0.5, pos(rng) + 0.5, pos(rng) + 0.5);
      if (c.kind == "stretched") stretch[0] = 10;
      if (c.kind == "compressed") stretch[0] = 0.1;
      if (c.kind == "inverted") stretch[2] = -pos(rng);
      if (c.kind == "inverted-symmetric") stretch = Vec3(1.5, 0.5, -0.5);  // two equal |sigma|
      Mat3 f = r * v * stretch.asDiagonal() * v.transpose();
      if (c.kind == "sheared") f(0, 1) += 3 * u(rng);
      c.f = f;
      cases.push_back(c);
    }
  }
  return cases;
}

/// Deformed vertices for F, rest centroid kept in place.
std::array<Vec3, 4> deform(const Case& c) {
  std::array<Vec3, 4> p;
  for (int a = 0; a < 4; ++a) p[a] = c.f * c.rest[a] + Vec3(0.3, -0.2, 0.1);
  return p;
}

TEST(HornMatrix, QuadraticFormIsTraceOfRotatedMatrix) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n;
  for (int i = 0; i < 100; ++i) {
    Mat3 m;
    for (int k = 0; k < 9; ++k) m(k / 3, k % 3) = n(rng);
    const Eigen::Quaterniond q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    const Eigen::Vector4d c(q.w(), q.x(), q.y(), q.z());
    EXPECT_NEAR(c.dot(horn_matrix(m) * c), (q.toRotationMatrix().transpose() * m).trace(),
                1e-13 * m.norm());
  }
}

TEST(RotationEnergy, QuadratureEqualsClosedForm) {
  for (const Case& c : catalogue(20, 9)) {
    const double volume = signed_volume(c.rest[0], c.rest[1], c.rest[2], c.rest[3]);
    const auto rest = quadrature_points(c.rest, volume);
    const auto deformed = quadrature_points(deform(c), volume);
    // Closed form from PAPER_NOTES: C = (V/20) sum_i y_i y_i^T over vertex offsets y_i;
    // E(Q) = tr(F C F^T) + tr(C) - 2 tr(Q^T F C).
    const Vec3 c0 = 0.25 * (c.rest[0] + c.rest[1] + c.rest[2] + c.rest[3]);
    Mat3 cm = Mat3::Zero();
    for (const Vec3& x : c.rest) cm += (x - c0) * (x - c0).transpose();
    cm *= volume / 20;
    std::mt19937 rng(3);
    for (int trial = 0; trial < 5; ++trial) {
      const Mat3 q = random_rotation(rng);
      const double closed = (c.f * cm * c.f.transpose()).trace() + cm.trace() -
                            2 * (q.transpose() * c.f * cm).trace();
      const double quadrature = rotation_energy(q, rest, deformed);
      const double scale = (c.f * cm * c.f.transpose()).trace() + cm.trace();
      EXPECT_NEAR(quadrature, closed, 1e-13 * scale) << c.kind;
    }
  }
}

TEST(RotationEnergy, NewtonExactSvdHornAndBruteForceAgree) {
  // 8 kinds x 130 = 1040 elements (fast default); the full sweep doubles it.
  const char* full = std::getenv("COROFEM_FULL");
  const auto cases = catalogue(full && std::string(full) == "1" ? 260 : 130, 21);
  ASSERT_GE(cases.size(), 1000u);
  int unique = 0, ambiguous = 0, newton_fallbacks = 0;
  double worst_newton = 0, worst_refs = 0, worst_brute = 0, worst_ambiguous_energy = 0;
  std::mt19937 rng(77);
  for (const Case& c : cases) {
    const double volume = signed_volume(c.rest[0], c.rest[1], c.rest[2], c.rest[3]);
    const auto rest = quadrature_points(c.rest, volume);
    const std::array<Vec3, 4> moved = deform(c);
    const auto deformed = quadrature_points(moved, volume);
    const std::vector<Vec3> positions(moved.begin(), moved.end());
    double a = 0;
    const Mat3 s = deformed_moment(moment_arms(rest), Tet{0, 1, 2, 3}, positions, a);
    const Mat3 exact = energy_exact_rotation(s);
    // Warm start within 0.3 rad of the answer, as from a previous time step.
    const Mat3 warm =
        Eigen::AngleAxisd(0.3, Vec3::Random().normalized()).toRotationMatrix() * exact;
    const NewtonOutcome newton = energy_newton_rotation(s, a, warm, 1e-14, 30);
    newton_fallbacks += newton.fell_back;
    const Mat3 svd = rotation_factor_svd(s);  // the oracle's SVD, not rotation/'s
    const Mat3 horn = rotation_factor_horn(s).toRotationMatrix();
    auto energy = [&](const Mat3& q) { return rotation_energy(q, rest, deformed); };
    const Mat3 brute = brute_force_minimize(energy, 4000, rng());
    // Uniqueness: the gap between N's two largest eigenvalues (the minimizer is unique iff > 0).
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(horn_matrix(s));
    const double gap = eig.eigenvalues()[3] - eig.eigenvalues()[2];
    const double e_exact = energy(exact);
    const double e_scale = a + rest.weight * 4;  // energy scale, >= the constant terms
    EXPECT_LE(e_exact, energy(brute) + 1e-12 * e_scale) << c.kind;
    if (gap > 1e-6 * s.norm()) {
      ++unique;
      worst_newton = std::max(worst_newton, angle_between(newton.rotation, exact));
      worst_refs = std::max({worst_refs, angle_between(svd, exact), angle_between(horn, exact)});
      // Brute force resolves the angle to ~sqrt(eps e_scale / gap): compare energies, and
      // angles only where the well is steep.
      if (gap > 1e-2 * s.norm()) worst_brute = std::max(worst_brute, angle_between(brute, exact));
    } else {
      ++ambiguous;
      for (const Mat3& q : {newton.rotation, svd, horn})
        worst_ambiguous_energy =
            std::max(worst_ambiguous_energy, std::abs(energy(q) - e_exact) / e_scale);
    }
  }
  std::cout << "[ energy ] " << unique << " unique, " << ambiguous << " ambiguous; newton-exact "
            << worst_newton << " rad, svd/horn-exact " << worst_refs << " rad, brute-exact "
            << worst_brute << " rad; ambiguous energy spread " << worst_ambiguous_energy
            << "; newton fallbacks " << newton_fallbacks << "\n";
  EXPECT_GT(unique, 900);
  EXPECT_GT(ambiguous, 0);  // the inverted-symmetric kind must exercise the non-unique case
  EXPECT_LT(worst_newton, 1e-10);
  EXPECT_LT(worst_refs, 1e-10);
  EXPECT_LT(worst_brute, 1e-5);
  EXPECT_LT(worst_ambiguous_energy, 1e-12);
}

TEST(RotationEnergy, BatchedNewtonIsTheElementwiseNewtonInEveryLane) {
  // The structure-of-arrays Newton of kNewtonLanes elements against the one-element routine on
  // the whole catalogue (regular to inverted, unique and ambiguous minimizers, so that lanes
  // converge at different iterations and some go to the elementwise fallback): the same
  // iteration counts and fallbacks, rotations equal to round-off (a few Newton steps of O(1)
  // numbers summed in another order: 1e-12). Warm starts from 0 to 1.2 rad off, and one lane
  // started at the answer (converged without a step: its Hessian check).
  const auto cases = catalogue(130, 21);
  std::vector<Mat3> s(cases.size()), warm(cases.size());
  std::vector<double> a(cases.size());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const double volume =
        signed_volume(cases[c].rest[0], cases[c].rest[1], cases[c].rest[2], cases[c].rest[3]);
    const std::array<Vec3, 4> moved = deform(cases[c]);
    const std::vector<Vec3> positions(moved.begin(), moved.end());
    s[c] = deformed_moment(moment_arms(quadrature_points(cases[c].rest, volume)), Tet{0, 1, 2, 3},
                           positions, a[c]);
    const double off = c % 7 == 0 ? 0.0 : 0.2 * static_cast<double>(c % 7);
    const Mat3 exact = energy_exact_rotation(s[c]);
    warm[c] =
        off == 0
            ? exact
            : Mat3(Eigen::AngleAxisd(off, Vec3::Random().normalized()).toRotationMatrix() * exact);
  }
  int fallbacks = 0, steps_differ = 0, unstepped = 0;
  double worst = 0;
  for (std::size_t first = 0; first + kNewtonLanes <= cases.size(); first += kNewtonLanes) {
    Mat3 ls[kNewtonLanes], lw[kNewtonLanes];
    double la[kNewtonLanes];
    NewtonOutcome batch[kNewtonLanes];
    for (int l = 0; l < kNewtonLanes; ++l) {
      ls[l] = s[first + l];
      lw[l] = warm[first + l];
      la[l] = a[first + l];
    }
    energy_newton_rotations(ls, la, lw, 1e-12, 30, batch);
    for (int l = 0; l < kNewtonLanes; ++l) {
      const NewtonOutcome one = energy_newton_rotation(ls[l], la[l], lw[l], 1e-12, 30);
      EXPECT_EQ(batch[l].fell_back, one.fell_back) << cases[first + l].kind;
      steps_differ += batch[l].iterations != one.iterations;
      fallbacks += one.fell_back;
      unstepped += one.iterations == 0;
      worst = std::max(worst, (batch[l].rotation - one.rotation).norm());
    }
  }
  std::cout << "[ energy ] batched Newton against elementwise: worst |dR| " << worst
            << ", fallbacks " << fallbacks << ", converged without a step " << unstepped << "\n";
  EXPECT_LT(worst, 1e-12);
  // A lane may take one step more or less only where the test sits at round-off of the tolerance.
  EXPECT_LE(steps_differ, 2);
  EXPECT_GT(unstepped, 0);
}

TEST(RotationEnergy, QuaternionOfRotationRoundTrips) {
  // quaternion_of_rotation against Eigen's (up to sign) and rotation_of_quaternion back to the
  // matrix, on random rotations and on the four branches' extremes (angle pi about each axis,
  // the identity), where a formula that divides by the wrong component loses every digit.
  std::mt19937 rng(5);
  std::vector<Mat3> rotations{Mat3::Identity()};
  for (int axis = 0; axis < 3; ++axis)
    rotations.push_back(Eigen::AngleAxisd(M_PI, Vec3::Unit(axis)).toRotationMatrix());
  for (int i = 0; i < 1000; ++i) rotations.push_back(random_rotation(rng));
  double worst_q = 0, worst_m = 0;
  for (const Mat3& r : rotations) {
    double m[9], q[4], back[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[3 * i + j] = r(i, j);
    quaternion_of_rotation(m, q);
    const Eigen::Quaterniond e(r);
    const double sign = q[0] * e.w() + q[1] * e.x() + q[2] * e.y() + q[3] * e.z() < 0 ? -1 : 1;
    worst_q = std::max({worst_q, std::abs(sign * q[0] - e.w()), std::abs(sign * q[1] - e.x()),
                        std::abs(sign * q[2] - e.y()), std::abs(sign * q[3] - e.z())});
    const double scaled[4] = {3 * q[0], 3 * q[1], 3 * q[2],
                              3 * q[3]};  // not unit: the 2 / |q|^2 form
    rotation_of_quaternion(scaled, back);
    for (int k = 0; k < 9; ++k) worst_m = std::max(worst_m, std::abs(back[k] - m[k]));
  }
  EXPECT_LT(worst_q, 1e-15 * 8);  // a few roundings of O(1) numbers
  EXPECT_LT(worst_m, 1e-15 * 8);
}

TEST(RotationEnergy, ExtractorMatchesTheExactMinimizerInBothKernelForms) {
  // The extractor's batches (moments, start, Newton and the rotation out, across lanes) in the
  // portable and the AVX2 form, against the exact minimizer per element (energy-exact), from a
  // cold start (identity) and warm (the previous frame's answer). 162 tets: the last batch is
  // partial. Large but not inverting deformations, so every minimizer is unique and Newton's
  // answer (tolerance 1e-13) must be the exact one to 1e-10 (the error in Q is about the
  // tolerance over the gap between N's top eigenvalues, of order 1 here).
  const TetMesh mesh = make_box_mesh({1, 0.8, 0.6}, {3, 3, 3});
  ASSERT_EQ(mesh.num_tets() % kNewtonLanes, 2);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  const Mat3 spin = Eigen::AngleAxisd(0.9, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<std::vector<Vec3>> frames(2);
  for (int f = 0; f < 2; ++f)
    for (const Vec3& x : mesh.rest)
      frames[f].push_back((f + 1) * 0.5 * spin *
                              Vec3(1.4 * x.x(), x.y() + 0.5 * x.x() * x.x(), 0.8 * x.z()) +
                          (1 - (f + 1) * 0.5) * x + Vec3(u(rng), u(rng), u(rng)));
  Parameters params;
  params.set("newton_tolerance", 1e-13);
  auto exact = make_rotation_extractor(RotationMethod::EnergyExact, mesh);
  const bool had_vector = set_vector_block_kernels(false);
  std::vector<std::vector<Mat3>> forms;
  std::vector<std::vector<std::uint8_t>> iterations;
  for (bool vector : {false, true}) {
    set_vector_block_kernels(vector);
    auto newton = make_rotation_extractor(RotationMethod::EnergyNewton, mesh, params);
    std::vector<Mat3> rotations(mesh.tets.size(), Mat3::Identity());
    for (const auto& positions : frames) {
      newton->extract(positions, rotations);
      std::vector<Mat3> oracle(mesh.tets.size(), Mat3::Identity());
      exact->extract(positions, oracle);
      EXPECT_EQ(newton->stats().fallbacks, 0);
      EXPECT_EQ(newton->stats().inverted, 0);
      double worst = 0;
      for (int e = 0; e < mesh.num_tets(); ++e)
        worst = std::max(worst, (rotations[e] - oracle[e]).norm());
      EXPECT_LT(worst, 1e-10) << (vector ? "vector" : "portable") << " form";
      EXPECT_GT(
          *std::max_element(newton->stats().iterations.begin(), newton->stats().iterations.end()),
          0);
    }
    forms.push_back(rotations);
    iterations.push_back(newton->stats().iterations);
  }
  set_vector_block_kernels(had_vector);
  double apart = 0;
  int steps_differ = 0;
  for (int e = 0; e < mesh.num_tets(); ++e) {
    apart = std::max(apart, (forms[0][e] - forms[1][e]).norm());
    steps_differ += iterations[0][e] != iterations[1][e];
  }
  if (vector_block_kernels())
    std::cout << "[ energy ] extractor, AVX2 against portable form: |dQ| " << apart << "\n";
  EXPECT_LT(apart, 1e-13);  // FMA against two roundings, a few Newton steps of O(1) numbers
  EXPECT_LE(steps_differ, 2);
}

TEST(RotationEnergy, NewtonDetectsSingularHessianAndFallsBack) {
  // S = R0 diag(1.5, 0.5, -0.5) with isotropic C: singular values 1.5, 0.5, 0.5 and det S < 0, so
  // a whole circle of rotations (R0 times the turns about x) minimizes E, and the Hessian at R0,
  // Newton's start, is singular along it; Newton must not divide by zero.
  const Mat3 r0 = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3 s = r0 * Vec3(1.5, 0.5, -0.5).asDiagonal();
  const NewtonOutcome out = energy_newton_rotation(s, 2.75, r0, 1e-12, 20);
  EXPECT_TRUE(out.fell_back) << "Newton went on through a singular Hessian";
  EXPECT_TRUE(out.rotation.allFinite());
  EXPECT_NEAR(out.rotation.determinant(), 1.0, 1e-12);
  // The maximum of tr(Q^T S) over proper rotations, analytic: s1 + s2 - s3 for det S < 0
  // (the proper rotation factor flips the smallest singular value's axis) = 1.5.
  EXPECT_NEAR((out.rotation.transpose() * s).trace(), 1.5, 1e-12);
}

}  // namespace
}  // namespace corofem
