#pragma once
// Error classes that map to the CLI's exit status: InputError -> 2, NotConverged / NumericalFault
// -> 1.
#include <stdexcept>
#include <string>

namespace corofem {

/// Bad input: a scene, mesh or output path the user must fix. The message names the file, key or
/// element at fault.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A solve that did not reach its tolerance within its iteration budget.
struct NotConverged : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// NaN or inf produced during a run (names the step and the first bad element).
struct NumericalFault : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace corofem
