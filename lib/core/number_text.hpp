#pragma once
// Numbers in messages as printf's %g writes them: 1e-08, 0.5, 1.26e-06 (std::to_string would
// write a tolerance of 1e-8 as 0.000000).
#include <cstdio>
#include <string>

#include "core/types.hpp"

namespace corofem {

inline std::string general_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// A point as "(x, y, z)", each coordinate as general_number writes it.
inline std::string point_text(const Vec3& p) {
  return "(" + general_number(p.x()) + ", " + general_number(p.y()) + ", " + general_number(p.z()) +
         ")";
}

}  // namespace corofem
