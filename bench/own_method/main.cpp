// corofem plus two methods of one's own: `own_method check` checks them against the oracles;
// anything else is the corofem command line (run, report, tune, compare, ...), which now also
// knows them.
#include <string>

#include "cli/entry_point.hpp"
#include "own_method.hpp"

int main(int argc, char** argv) {
  own::register_energy_mueller();
  own::register_damped_l1_jacobi();
  if (argc == 2 && std::string(argv[1]) == "check") return own::check_against_oracles();
  return corofem::cli::main(argc, argv);
}
