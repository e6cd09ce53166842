#pragma once
// Numbers in messages as printf's %g writes them: 1e-08, 0.5, 1.26e-06 (std::to_string would
// write a tolerance of 1e-8 as 0.000000).
#include <cstdio>
#include <string>

namespace corofem {

inline std::string general_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace corofem
