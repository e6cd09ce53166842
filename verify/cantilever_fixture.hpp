#pragma once
// A cantilever bar L x h x h under gravity, fixed at x = 0: the gates' standard static problem.
#include "fem/fe_problem.hpp"
#include "fem/loads.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/vertex_selection.hpp"

namespace corofem::test {

struct Cantilever {
  double length = 1, height = 0.1, young = 5e6, poisson = 0.3, density = 1000, gravity = 9.81;

  /// nx = 10 k cells along the bar, k across.
  FeProblem build(int k, double gravity_scale = 1.0) const {
    TetMesh mesh = make_box_mesh({length, height, height}, {10 * k, k, k});
    std::vector<Material> m(mesh.tets.size(), Material{young, poisson, density});
    FeProblem p = make_fe_problem(std::move(mesh), std::move(m));
    for (int v : vertices_in_box(p.mesh.rest, {Vec3::Zero(), Vec3(0, height, height)}))
      p.dirichlet.fix_vertex(v);
    p.external_force = gravity_load(p.mesh, p.materials, Vec3(0, 0, -gravity * gravity_scale));
    return p;
  }

  /// Mean displacement of the tip face x = L.
  static Vec3 tip_displacement(const FeProblem& p, const Eigen::VectorXd& u) {
    const double lx = p.mesh.rest[p.mesh.num_vertices() - 1].x();
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (int v = 0; v < p.mesh.num_vertices(); ++v)
      if (std::abs(p.mesh.rest[v].x() - lx) < 1e-12) {
        sum += u.segment<3>(3 * v);
        ++n;
      }
    return sum / n;
  }

  /// Timoshenko beam tip deflection under uniform load q = rho g A (shear factor 5/6).
  double beam_theory_deflection(double gravity_scale = 1.0) const {
    const double area = height * height, inertia = std::pow(height, 4) / 12;
    const double q = density * gravity * gravity_scale * area;
    const double shear = young / (2 * (1 + poisson));
    return q * std::pow(length, 4) / (8 * young * inertia) +
           q * length * length / (2 * 5.0 / 6.0 * shear * area);
  }
};

}  // namespace corofem::test
