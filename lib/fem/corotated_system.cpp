#include "fem/corotated_system.hpp"

#include <Eigen/LU>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "fem/corotated_assembly.hpp"

namespace corofem {

void linearize(FeProblem& problem, RotationExtractor& extractor, const std::vector<Vec3>& positions,
               const Eigen::VectorXd& displacement, std::vector<Mat3>& rotations,
               Eigen::VectorXd& force, PhaseClock& clock, const AssemblyTarget& target) {
  clock.time("rotate", [&] { extractor.extract(positions, rotations); });
  clock.time("assemble", [&] {
    assemble_corotated(problem.elements, problem.mesh, problem.assembly, rotations, displacement,
                       target.matrix ? *target.matrix : problem.stiffness, force, target.scale,
                       target.diagonal);
  });
}

int count_inverted(const FeProblem& problem, const std::vector<Vec3>& positions,
                   const std::vector<char>* only) {
  int inverted = 0;
#pragma omp parallel for schedule(static) reduction(+ : inverted) num_threads(threads_for(problem.mesh.num_tets()))
  for (int e = 0; e < problem.mesh.num_tets(); ++e) {
    if (only && !(*only)[e]) continue;
    const Mat3 f = deformation_gradient(problem.elements[e].rest_edge_inverse(), positions,
                                        problem.mesh.tets[e]);
    if (f.determinant() <= 0) ++inverted;
  }
  return inverted;
}

void check_finite(const FeProblem& problem, const Eigen::VectorXd& u, const std::string& what,
                  const std::string& where) {
  // Finite entries whose norm overflows are as unusable (every norm, residual and energy of them
  // is inf): they fail too, located at the largest entry.
  if (std::isfinite(u.squaredNorm()))
    return;  // one pass: a NaN or inf entry makes it non-finite too
  const bool entries_finite = u.allFinite();
  const double largest = entries_finite ? u.cwiseAbs().maxCoeff() : 0.0;
  const auto bad = [&](int v) {
    const auto s = u.segment<3>(3 * v);
    return entries_finite ? s.cwiseAbs().maxCoeff() == largest : !s.allFinite();
  };
  const std::string fault = "non-finite " + what + (entries_finite ? " norm" : "") + " at " + where;
  for (int e = 0; e < problem.mesh.num_tets(); ++e)
    for (int v : problem.mesh.tets[e])
      if (bad(v))
        throw NumericalFault(fault + ", first at element " +
                             std::to_string(problem.mesh.element_tags[e]) + " (node " +
                             std::to_string(problem.mesh.node_tags[v]) + ")");
  throw NumericalFault(fault);
}

}  // namespace corofem
