#pragma once
// The multigrid smoother of every level but the coarsest, behind one interface: its set-up on the
// level's matrix, pre- and post-smoothing, the bytes and flops the step's roofline counts for
// each, and what the record says of it. Each smoother registers one traits record beside its
// implementation (the `*_smoother*()` function its header declares); a user's program registers
// its own with register_smoother before it runs anything (lib/docs/extending.md), and scenes then
// name it in analysis.smoother.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/parameters.hpp"
#include "sparse/matrix_traffic.hpp"

namespace corofem {

class Smoother {
 public:
  virtual ~Smoother() = default;
  /// Set-up on the level's matrix; again whenever its values change.
  virtual void set_matrix(const BrcMatrix& a) = 0;
  /// `sweeps` smoothing steps for A x = b before the coarse correction, from x (from x = 0 with
  /// `zero_guess`, whatever x holds, also with no sweeps). Where it forms r = b - A x of the x
  /// it leaves in passing, it writes `r` and returns true; false and the caller forms it.
  virtual bool pre_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          int sweeps, bool zero_guess, Eigen::VectorXd& r) const = 0;
  /// `sweeps` steps after the coarse correction. Pre and post together keep the V-cycle a
  /// symmetric preconditioner for CG (the post-smoother is the pre-smoother's adjoint).
  virtual void post_smooth(const BrcMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                           int sweeps) const = 0;
  /// Whether pre_smooth from x = 0 with `sweeps` forms the residual (returns true).
  virtual bool forms_residual(int sweeps) const = 0;
  /// The roofline's counts: of set_matrix, of pre_smooth from x = 0 (with the residual where it
  /// forms it), of post_smooth.
  virtual Traffic setup_traffic(const BrcMatrix& a) const = 0;
  virtual Traffic pre_traffic(const BrcMatrix& a, int sweeps) const = 0;
  virtual Traffic post_traffic(const BrcMatrix& a, int sweeps) const = 0;
  /// What it is, for the run's record: "kind" and its parameters.
  virtual Parameters describe() const = 0;
};

/// A smoother as scenes name it: its settings, declared (each a scene key of `analysis`, with
/// its default and range: the scene reader reads them by this alone), and how to make it from
/// their values.
struct SmootherTraits {
  std::string name{};  ///< the scene's analysis.smoother
  std::vector<ParameterSpec> parameters{};
  std::function<std::unique_ptr<Smoother>(const Parameters&)> make{};
};

/// Adds a smoother; its name must be new.
void register_smoother(SmootherTraits traits);
/// Every registered smoother's name, built-ins first.
std::vector<std::string> smoother_names();
/// The smoother named `name`, or null.
const SmootherTraits* find_smoother(std::string_view name);
/// A new smoother named `name` with `values` (its declared settings that `values` lacks at their
/// defaults, others ignored); std::out_of_range naming the registered ones for another name.
std::unique_ptr<Smoother> make_smoother(std::string_view name, const Parameters& values = {});
/// Every registered smoother's declared settings (the scene keys that belong to smoothers).
std::vector<ParameterSpec> smoother_parameters();

}  // namespace corofem
