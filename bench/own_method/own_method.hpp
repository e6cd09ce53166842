#pragma once
// The example's two methods: their scene names and registrations, and the checks against the
// oracles.
namespace own {

inline constexpr const char* kEnergyMueller = "energy-mueller-3";
inline constexpr const char* kDampedL1Jacobi = "damped-l1-jacobi";

void register_energy_mueller();
void register_damped_l1_jacobi();
/// A report section of its own: Table 1's phases for both methods beside the paper's method
/// (`own_method report --own-methods-only`; renderer unit report_sections/own_methods.py).
void register_own_table();

/// 0 when both agree with their oracles (the exact minimizer; CHOLMOD), else 1; says why on
/// stderr.
int check_against_oracles();

}  // namespace own
