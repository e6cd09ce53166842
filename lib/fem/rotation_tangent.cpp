#include "fem/rotation_tangent.hpp"

#include <stdexcept>

#include "rotation/energy_rotation.hpp"
#include "rotation/gram_schmidt_frame.hpp"

namespace corofem {

namespace {

Mat3 cross_matrix(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

/// Derivative of v / |v| in direction dv.
Vec3 unit_derivative(const Vec3& v, const Vec3& dv) {
  const double n = v.norm();
  const Vec3 e = v / n;
  return (dv - e * e.dot(dv)) / n;
}

/// Derivative of edge_frame(x0, x1, x2) when d1 = x1 - x0 and d2 = x2 - x0 move by dd1, dd2.
Mat3 edge_frame_derivative(const Vec3& d1, const Vec3& d2, const Vec3& dd1, const Vec3& dd2) {
  const Vec3 e1 = d1.normalized();
  const Vec3 de1 = unit_derivative(d1, dd1);
  const Vec3 w = d2 - d2.dot(e1) * e1;
  const Vec3 dw = dd2 - (dd2.dot(e1) + d2.dot(de1)) * e1 - d2.dot(e1) * de1;
  const Vec3 e2 = w.normalized();
  const Vec3 de2 = unit_derivative(w, dw);
  Mat3 dg;
  dg << de1, de2, de1.cross(e2) + e1.cross(de2);
  return dg;
}

}  // namespace

Mat3 rotation_factor_derivative(const Mat3& q, const Mat3& l, const Mat3& dl) {
  Mat3 u = q.transpose() * l;
  u = 0.5 * (u + u.transpose()).eval();
  const Mat3 a = u.trace() * Mat3::Identity() - u;
  const Mat3 k = q.transpose() * dl - dl.transpose() * q;  // = [ (tr(U) I - U) w ]x
  const Vec3 b(k(2, 1), k(0, 2), k(1, 0));
  const double det = a.determinant();
  if (!(std::abs(det) > 1e-14 * std::pow(a.norm(), 3))) return Mat3::Zero();
  return q * cross_matrix(a.inverse() * b);
}

double asymmetry(const Mat12& j) {
  const double n = j.norm();
  return n > 0 ? (j - j.transpose()).norm() / n : 0.0;
}

RotationTangent::RotationTangent(const FeProblem& problem, RotationMethod method)
    : problem_(problem), family_(method.traits().tangent), exact_(method.traits().tangent_exact) {
  const TetMesh& mesh = problem.mesh;
  if (family_ == TangentFamily::PolarOfF) {
    model_ = "rotation factor of F";
    h_.resize(mesh.tets.size());
    for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
      // F = sum_b (x_b - x_0) B.row(b-1), B = Dm^{-1}.
      const Mat3 b = problem.elements[e].rest_edge_inverse();
      h_[e][0] = -(b.row(0) + b.row(1) + b.row(2)).transpose();
      for (int v = 1; v < 4; ++v) h_[e][v] = b.row(v - 1).transpose();
    }
  } else if (family_ == TangentFamily::MomentFactor) {
    model_ = "rotation factor of S = F C (eq. 3)";
    // S = sum_v p_v h_v^T: dS/dp_v = h_v, the moment arms (element_quadrature.hpp).
    const std::vector<MomentArms> rest = rest_moment_arms(mesh);
    h_.resize(mesh.tets.size());
    for (std::size_t e = 0; e < mesh.tets.size(); ++e) h_[e] = rest[e].h;
  } else if (family_ == TangentFamily::GramSchmidt) {
    model_ = "Gram-Schmidt frame of edges 0-1, 0-2";
    for (const Tet& t : mesh.tets)
      rest_frame_.push_back(edge_frame(mesh.rest[t[0]], mesh.rest[t[1]], mesh.rest[t[2]]));
  } else {
    model_ = "identity";
  }
}

void RotationTangent::rotation_jacobian(int e, const std::vector<Vec3>& positions, const Mat3& q,
                                        RotationJacobian& dq) const {
  const Tet& t = problem_.mesh.tets[e];
  switch (family_) {
    case TangentFamily::Identity:
      for (Mat3& d : dq) d.setZero();
      return;
    case TangentFamily::GramSchmidt: {
      const Vec3 d1 = positions[t[1]] - positions[t[0]], d2 = positions[t[2]] - positions[t[0]];
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) {
          const Vec3 unit = Vec3::Unit(c);
          const Vec3 dd1 = ((a == 1) - (a == 0)) * unit, dd2 = ((a == 2) - (a == 0)) * unit;
          dq[3 * a + c] = edge_frame_derivative(d1, d2, dd1, dd2) * rest_frame_[e].transpose();
        }
      return;
    }
    case TangentFamily::PolarOfF:
    case TangentFamily::MomentFactor: {
      Mat3 l = Mat3::Zero();  // L = sum_v p_v h_v^T (F, or S: both linear in the positions)
      for (int v = 0; v < 4; ++v) l.noalias() += positions[t[v]] * h_[e][v].transpose();
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c)
          dq[3 * a + c] = rotation_factor_derivative(q, l, Vec3::Unit(c) * h_[e][a].transpose());
      return;
    }
  }
}

Mat12 RotationTangent::element_jacobian(int e, const std::vector<Vec3>& positions,
                                        const Mat3& q) const {
  const Tet& t = problem_.mesh.tets[e];
  const Mat12 k = problem_.elements[e].stiffness();
  // The force as internal_forces() computes it: s_0 = 0, s_b = Q^T (x_b - x_0) - (X_b - X_0).
  Vec12 s = Vec12::Zero();
  for (int b = 1; b < 4; ++b)
    s.segment<3>(3 * b) = q.transpose() * (positions[t[b]] - positions[t[0]]) -
                          (problem_.mesh.rest[t[b]] - problem_.mesh.rest[t[0]]);
  const Vec12 ks = k * s;
  RotationJacobian dq;
  rotation_jacobian(e, positions, q, dq);
  Mat12 j;
  for (int a = 0; a < 4; ++a)
    for (int c = 0; c < 3; ++c) {
      const int col = 3 * a + c;
      Vec12 ds = Vec12::Zero();
      for (int b = 1; b < 4; ++b) {
        ds.segment<3>(3 * b) = dq[col].transpose() * (positions[t[b]] - positions[t[0]]);
        const int moved = (a == b) - (a == 0);
        if (moved != 0) ds.segment<3>(3 * b) += moved * q.row(c).transpose();  // Q^T e_c
      }
      const Vec12 kds = k * ds;
      for (int v = 0; v < 4; ++v)
        j.block<3, 1>(3 * v, col) = dq[col] * ks.segment<3>(3 * v) + q * kds.segment<3>(3 * v);
    }
  return j;
}

void RotationTangent::assemble(const std::vector<Vec3>& positions,
                               const std::vector<Mat3>& rotations, BrcMatrix& out) const {
  out.set_zero();
  for (int e = 0; e < problem_.mesh.num_tets(); ++e) {
    const Mat12 j = element_jacobian(e, positions, rotations[e]);
    const auto& blocks = problem_.assembly.block[e];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) out.block(blocks[4 * a + b]) += j.block<3, 3>(3 * a, 3 * b);
  }
}

}  // namespace corofem
