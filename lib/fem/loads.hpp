#pragma once
// Lumped mass and external loads, as DOF vectors (index 3*vertex + component).
#include <Eigen/Core>
#include <vector>

#include "element/material.hpp"

namespace corofem {

/// Lumped mass per DOF: each vertex gets rho V / 4 from every element around it.
Eigen::VectorXd lumped_mass(const TetMesh& mesh, const std::vector<Material>& materials);

/// Body load rho g V / 4 per vertex per element.
Eigen::VectorXd gravity_load(const TetMesh& mesh, const std::vector<Material>& materials,
                             const Vec3& gravity);

/// Adds `total` spread equally over `vertices` to `f`; with `among` > 0, a share of total / among
/// to each (`vertices` is one rank's part of a selection of `among` vertices).
void add_spread_force(Eigen::VectorXd& f, const std::vector<int>& vertices, const Vec3& total,
                      int among = 0);

}  // namespace corofem
