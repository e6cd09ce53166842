#pragma once
// The `corofem` command as a function: a user's program registers its own methods
// (lib/docs/extending.md) and then hands its arguments here, so that its executable is corofem
// plus those methods.
namespace corofem::cli {

/// Runs the command line as `corofem` does; returns its exit status (0 success, 1 did not
/// converge or numerical fault, 2 bad input, 3 internal error). Under mpirun a failure stops
/// every rank.
int main(int argc, char** argv);

}  // namespace corofem::cli
