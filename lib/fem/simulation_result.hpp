#pragma once
// What a static or dynamic solve returns, and the per-phase clock shared by both.
#include <Eigen/Core>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "core/event_observer.hpp"
#include "element/element_stiffness.hpp"

namespace corofem {

/// Static Newton by GMRES on the multigrid: the tangents whose symmetric part the multigrid could
/// not take (indefinite: a body in compression), preconditioned instead on the definite stand-in,
/// and those the sparse factorizations took where that missed too.
struct TangentFallbacks {
  int standin = 0;
  int factored = 0;
};

struct SimulationResult {
  Eigen::VectorXd displacement;  ///< per DOF
  std::vector<Mat3> rotations;   ///< per element, of the final state
  bool converged = false;
  int iterations = 0;      ///< static: rotation/solve iterations over all increments
  int steps = 0;           ///< dynamic: time steps taken; static: load increments converged
  int increment_cuts = 0;  ///< static Newton: load increments halved after not converging
  TangentFallbacks tangent_fallbacks;  ///< static Newton by GMRES on the multigrid
  int step_cuts = 0;                   ///< dynamic Newton: time steps halved after not converging
  int newton_at_floor = 0;             ///< dynamic Newton: steps converged at the rounding floor
  int newton_halvings = 0;             ///< Newton: step lengths halved by its line search, in all
  int potential_fallbacks = 0;  ///< Newton: steps whose search on the potential found no decrease
  double residual = 0;          ///< |f_ext - f_int| / |f_ext| over free DOFs, final state
  int inverted_max = 0;         ///< most elements with det F <= 0 seen at any iteration or step
  int linear_iterations = 0;    ///< V-cycles / CG iterations summed (1 per direct solve)
  double last_solve_residual = 0;  ///< dynamic: the last step's linear solve, |b - A x| / |b|
  std::map<std::string, double> timings_ms;  ///< phase -> total milliseconds
  std::string message;                       ///< why it did not converge, if it did not
};

/// Accumulates wall time per phase into SimulationResult::timings_ms, and marks each phase as a
/// section for `sections` (counted runs: core/section_counter.hpp).
class PhaseClock {
 public:
  explicit PhaseClock(std::map<std::string, double>& totals, EventObserver* sections = nullptr)
      : totals_(totals), sections_(sections) {}
  template <class F>
  auto time(const std::string& phase, F&& f) {
    const auto start = std::chrono::steady_clock::now();
    struct Add {
      std::map<std::string, double>& totals;
      const std::string& phase;
      std::chrono::steady_clock::time_point start;
      ~Add() {
        totals[phase] +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
      }
    } add{totals_, phase, start};
    return in_section(sections_, phase, std::forward<F>(f));
  }

 private:
  std::map<std::string, double>& totals_;
  EventObserver* sections_;
};

}  // namespace corofem
