#pragma once
// The oracles the report's verification summary checks its runs against, as a seam: lib/ never
// links them (they live in reference/, deliberately simple and off the production path of
// `corofem run`); the executable wires them before it runs anything (cli/main.cpp, or a user's
// program, bench/own_method/main.cpp). A report asked to check a run with no oracle wired
// refuses, naming what is missing, rather than record a check it did not make.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

namespace corofem {

struct ReportOracles {
  /// x with A x = b by a direct solve (reference::cholmod_solve).
  std::function<Eigen::VectorXd(const Eigen::SparseMatrix<double>&, const Eigen::VectorXd&)>
      direct_solve{};
  /// R A R^T by a general sparse product (reference::eigen_galerkin).
  std::function<Eigen::SparseMatrix<double>(const Eigen::SparseMatrix<double>& r,
                                            const Eigen::SparseMatrix<double>& a)>
      galerkin{};
};

/// Wires the oracles (before any run; read from the report's runs after).
void set_report_oracles(ReportOracles oracles);
/// The wired oracles; std::logic_error naming `which` when that one is not wired.
const ReportOracles& report_oracles(const char* which);

}  // namespace corofem
