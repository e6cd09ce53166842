#include "report/report_oracles.hpp"

#include <stdexcept>
#include <string>

namespace corofem {
namespace {

ReportOracles& wired() {
  static ReportOracles oracles;
  return oracles;
}

}  // namespace

void set_report_oracles(ReportOracles oracles) {
  wired() = std::move(oracles);
}

const ReportOracles& report_oracles(const char* which) {
  const ReportOracles& o = wired();
  const bool missing = std::string(which) == "direct_solve" ? !o.direct_solve : !o.galerkin;
  if (missing)
    throw std::logic_error(std::string("the report's oracle '") + which +
                           "' is not wired: the executable sets it with set_report_oracles "
                           "(cli/main.cpp does, with reference/'s)");
  return o;
}

}  // namespace corofem
