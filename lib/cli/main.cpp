// corofem: command-line harness. Exit status: 0 success, 1 did not converge or numerical fault,
// 2 bad input (scene, mesh, arguments, unwritable output), 3 internal error. The report's
// verification summary checks against reference/'s oracles, wired here: lib/ never links them.
#include "cholmod_oracle.hpp"
#include "cli/entry_point.hpp"
#include "galerkin_oracle.hpp"
#include "report/report_oracles.hpp"

int main(int argc, char** argv) {
  corofem::set_report_oracles({.direct_solve = corofem::reference::cholmod_solve,
                               .galerkin = corofem::reference::eigen_galerkin});
  return corofem::cli::main(argc, argv);
}
