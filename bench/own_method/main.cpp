// corofem plus two methods of one's own: `own_method check` checks them against the oracles;
// anything else is the corofem command line (run, report, tune, compare, ...), which now also
// knows them.
#include <string>

#include "cholmod_oracle.hpp"
#include "cli/entry_point.hpp"
#include "galerkin_oracle.hpp"
#include "own_method.hpp"
#include "report/report_oracles.hpp"

int main(int argc, char** argv) {
  // The report's verification summary checks against reference/'s oracles, as corofem's does.
  corofem::set_report_oracles({.direct_solve = corofem::reference::cholmod_solve,
                               .galerkin = corofem::reference::eigen_galerkin});
  own::register_energy_mueller();
  own::register_damped_l1_jacobi();
  own::register_own_table();
  if (argc == 2 && std::string(argv[1]) == "check") return own::check_against_oracles();
  return corofem::cli::main(argc, argv);
}
