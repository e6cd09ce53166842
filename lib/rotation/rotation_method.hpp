#pragma once
// The rotation extraction methods (PAPER_NOTES section 2) and their scene names.
#include "core/name_table.hpp"

namespace corofem {

enum class RotationMethod {
  EnergyNewton,   ///< the paper's energy minimization, quaternion Newton (section 4)
  EnergyExact,    ///< the closed-form minimizer of the same energy (Horn's quaternion)
  Polar,          ///< polar decomposition of F
  PolarFixed,     ///< SVD of F with inversion handling (Irving et al.)
  PolarSmoothed,  ///< polar, then 1-ring quaternion averaging (paper section 5)
  Qr,             ///< Gram-Schmidt frame of the edges
  Mueller2016,    ///< Mueller et al. 2016's iteration on F
  None,           ///< identity: the linear formulation
};

inline constexpr NameTable<RotationMethod, 8> kRotationMethods{{{
    {RotationMethod::EnergyNewton, "energy-newton"},
    {RotationMethod::EnergyExact, "energy-exact"},
    {RotationMethod::Polar, "polar"},
    {RotationMethod::PolarFixed, "polar-fixed"},
    {RotationMethod::PolarSmoothed, "polar-smoothed"},
    {RotationMethod::Qr, "qr"},
    {RotationMethod::Mueller2016, "mueller2016"},
    {RotationMethod::None, "none"},
}}};

}  // namespace corofem
