// corofem: command-line harness. Exit status: 0 success, 1 did not converge or numerical fault,
// 2 bad input (scene, mesh, arguments, unwritable output), 3 internal error.
#include "cli/entry_point.hpp"

int main(int argc, char** argv) {
  return corofem::cli::main(argc, argv);
}
