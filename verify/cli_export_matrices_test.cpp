// export-matrices: the files read back give A<h+1> = R<h> A<h> R<h>^T (Eigen product as oracle),
// sizes match levels.json, and A0 is symmetric; X0 holds the fine vertices' positions in A0's order
// (the stiffness annihilates the rigid motion built from them).
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

#include "galerkin_oracle.hpp"
#include "io/matrix_market.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

/// export-matrices of a box clamped at x = 0 under gravity, with `analysis`, into dir / "out".
test::CliResult export_box(const test::TempDir& dir, const std::string& analysis) {
  test::write_text(dir / "scene.json", R"({
    "mesh": {"box": [1, 0.5, 0.5], "cells": [8, 4, 4]},
    "material": {"young": 1e6, "poisson": 0.3, "density": 1000},
    "fixed": [{"box": [[0, 0, 0], [0, 0.5, 0.5]]}],
    "gravity": [0, 0, -9.81],
    "analysis": )" + analysis + "}");
  return test::run_cli("export-matrices '" + (dir / "scene.json").string() + "' --out '" +
                       (dir / "out").string() + "'");
}

TEST(CliExportMatrices, LevelsAreGalerkinProductsOfTheFiles) {
  test::TempDir dir;
  const auto r = export_box(
      dir, R"({"type": "dynamic", "solver": "mgpcg", "levels": 3, "dt": 0.01, "steps": 5})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto levels = nlohmann::json::parse(test::read_text(dir / "out/levels.json"));
  ASSERT_EQ(levels["levels"].size(), 3u);
  for (int h = 0; h < 3; ++h) {
    const auto a = read_matrix_market(dir / ("out/A" + std::to_string(h) + ".mtx"));
    EXPECT_EQ(a.rows(), levels["levels"][h]["dofs"].get<long>());
    EXPECT_LT((Eigen::MatrixXd(a) - Eigen::MatrixXd(a).transpose()).norm(), 1e-12 * a.norm());
    if (h == 0) continue;
    const auto below = read_matrix_market(dir / ("out/A" + std::to_string(h - 1) + ".mtx"));
    const auto rh = read_matrix_market(dir / ("out/R" + std::to_string(h - 1) + ".mtx"));
    EXPECT_EQ(rh.rows(), a.rows());
    EXPECT_EQ(rh.cols(), below.rows());
    // 17 significant digits in the files: the product agrees to round-off.
    const Eigen::SparseMatrix<double> ref = reference::eigen_galerkin(rh, below);
    EXPECT_LT((Eigen::MatrixXd(a) - Eigen::MatrixXd(ref)).norm(), 1e-13 * ref.norm())
        << "level " << h;
  }
}

// The static first iteration's A0 is the rest stiffness K with supports imposed. K annihilates
// every rigid motion, so a rotation built from X0's positions gives A0 r = 0 on the rows of
// vertices with no fixed neighbour, up to round-off; were X0 in another order than A0's DOFs, or
// wrong, it would not. A quadratic field built from the same positions (constant body force in the
// interior) is not annihilated: the bound discriminates.
TEST(CliExportMatrices, CoordinatesAreTheFineVerticesInTheMatrixOrder) {
  test::TempDir dir;
  const auto r = export_box(dir, R"({"type": "static", "solver": "mgpcg", "levels": 2})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto levels = nlohmann::json::parse(test::read_text(dir / "out/levels.json"));
  EXPECT_EQ(levels["levels"][0]["coordinates"]["file"], "X0.mtx");
  const Eigen::MatrixXd x = Eigen::MatrixXd(read_matrix_market(dir / "out/X0.mtx"));
  const auto a = read_matrix_market(dir / "out/A0.mtx");
  ASSERT_EQ(x.cols(), 3);
  ASSERT_EQ(3 * x.rows(), a.rows());
  EXPECT_EQ(x.rows(), levels["levels"][0]["vertices"].get<long>());
  EXPECT_NEAR(x.col(0).maxCoeff(), 1.0, 1e-12);  // the box's far end
  const Eigen::Vector3d centre(0.5, 0.25, 0.25), axis = Eigen::Vector3d(1, 2, 3).normalized();
  Eigen::VectorXd rotation(a.rows()), quadratic = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d p = x.row(v).transpose() - centre;
    rotation.segment<3>(3 * v) = axis.cross(p);
    quadratic(3 * v) = p.x() * p.x();
  }
  const Eigen::VectorXd ar = a * rotation, aq = a * quadratic;
  double worst_rotation = 0, least_quadratic = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    if (x(v, 0) < 0.2) continue;  // within one cell (0.125) of the fixed end x = 0
    worst_rotation = std::max(worst_rotation, ar.segment<3>(3 * v).norm());
    least_quadratic = std::min(least_quadratic, std::abs(aq(3 * v)));
  }
  // Round-off: 17 digits in the files, some 30 terms a row: 1e-14 of |A|max |r|max at most.
  const double scale = a.coeffs().cwiseAbs().maxCoeff() * rotation.cwiseAbs().maxCoeff();
  EXPECT_LT(worst_rotation, 1e-12 * scale);
  // The quadratic field's nodal forces, div sigma = (lambda + 2 mu) 2 times a vertex's volume
  // share, are some 3e-3 of the scale at the least (measured): far above the bound.
  EXPECT_GT(least_quadratic, 1e-6 * scale);
}

}  // namespace
}  // namespace corofem
