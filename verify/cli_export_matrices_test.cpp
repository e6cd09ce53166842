// export-matrices: the files read back give A<h+1> = R<h> A<h> R<h>^T (Eigen product as oracle),
// sizes match levels.json, and A0 is symmetric.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "galerkin_oracle.hpp"
#include "io/matrix_market.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

TEST(CliExportMatrices, LevelsAreGalerkinProductsOfTheFiles) {
  test::TempDir dir;
  test::write_text(dir / "scene.json", R"({
    "mesh": {"box": [1, 0.5, 0.5], "cells": [8, 4, 4]},
    "material": {"young": 1e6, "poisson": 0.3, "density": 1000},
    "fixed": [{"box": [[0, 0, 0], [0, 0.5, 0.5]]}],
    "gravity": [0, 0, -9.81],
    "analysis": {"type": "dynamic", "solver": "mgpcg", "levels": 3, "dt": 0.01, "steps": 5}
  })");
  const auto r = test::run_cli("export-matrices '" + (dir / "scene.json").string() + "' --out '" +
                               (dir / "out").string() + "'");
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

}  // namespace
}  // namespace corofem
