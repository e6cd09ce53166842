#include "cli/entry_point.hpp"

#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "solver/mpi_launch.hpp"

namespace corofem::cli {
namespace {

int run(const std::vector<std::string>& args) {
  try {
    return dispatch(args);
  } catch (const InputError& e) {
    // Every rank reads the same scene and meets the same bad input: rank 0 says it, once.
    if (launcher_rank() == 0) std::cerr << "corofem: error: " << e.what() << "\n";
    return 2;
  } catch (const NumericalFault& e) {
    std::cerr << "corofem: numerical fault: " << e.what() << "\n";
    return 1;
  } catch (const NotConverged& e) {
    std::cerr << "corofem: did not converge: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "corofem: error: out of memory\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "corofem: internal error: " << e.what() << "\n";
    return 3;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  remove_partial_outputs_on_interrupt();
  const int status = run(args);
  // Under mpirun: no rank may be left waiting in a collective call for one that stopped.
  if (status != 0) abort_all_ranks(status);
  return status;
}

}  // namespace corofem::cli
