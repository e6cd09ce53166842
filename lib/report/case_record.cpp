#include "report/case_record.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace corofem {

nlohmann::json record_case(nlohmann::json base, const std::function<nlohmann::json()>& f) {
  try {
    nlohmann::json record = f();
    for (auto& [key, value] : record.items()) base[key] = value;
    base["completed"] = true;
  } catch (const InputError& e) {
    base["completed"] = false;
    base["error"] = {{"kind", "input"}, {"message", e.what()}};
  } catch (const NumericalFault& e) {
    base["completed"] = false;
    base["error"] = {{"kind", "numerical"}, {"message", e.what()}};
  } catch (const NotConverged& e) {
    base["completed"] = false;
    base["error"] = {{"kind", "not_converged"}, {"message", e.what()}};
  } catch (const std::exception& e) {
    base["completed"] = false;
    base["error"] = {{"kind", "internal"}, {"message", e.what()}};
  }
  return base;
}

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace corofem
