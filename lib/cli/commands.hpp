#pragma once
// The CLI's commands; main() only maps exceptions to exit codes.
#include <string>
#include <vector>

namespace corofem {

/// Runs the command named by args[0]; returns the exit status.
int dispatch(const std::vector<std::string>& args);

}  // namespace corofem
