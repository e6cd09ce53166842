#pragma once
// What `corofem tune` measures a setting's error on, and the error between two runs that may sit
// on different meshes of the same body (a coarser resolution against the reference): the
// reference's field is interpolated at the other run's points (multigrid/point_location, which
// reproduces affine fields exactly), so no mesh has to be nested in another.
#include <Eigen/Core>
#include <vector>

#include "core/name_table.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/vertex_selection.hpp"

namespace corofem {

enum class TuneQuantity { Displacement, Tip, Probe };
inline constexpr NameTable<TuneQuantity, 3> kTuneQuantities{{{
    {TuneQuantity::Displacement, "displacement"},  // the whole final field
    {TuneQuantity::Tip, "tip"},                    // the final displacement at one point
    {TuneQuantity::Probe, "probe"},                // mean final displacement over a box
}}};

struct QuantitySpec {
  TuneQuantity kind = TuneQuantity::Displacement;
  AxisBox probe{};          ///< Probe: the box
  Vec3 tip = Vec3::Zero();  ///< Tip: the point (tip_point)
};

/// A run's final state on its own mesh.
struct FinalState {
  TetMesh mesh;
  Eigen::VectorXd displacement;  ///< per DOF, 3 per vertex
};

/// Relative error of `candidate`'s quantity against `reference`'s:
/// displacement: |u_c - I u_r| / |I u_r| over the candidate's vertices (I: interpolation of the
///   reference's field at them; the identity on the same mesh);
/// tip: |u_c(p) - u_r(p)| / |u_r(p)|, each field interpolated at the tip p;
/// probe: |m_c - m_r| / |m_r|, m a field's mean over the reference's vertices in the box.
/// Absolute where the reference's quantity is zero.
double quantity_error(const QuantitySpec& quantity, const FinalState& candidate,
                      const FinalState& reference);

/// The reference body's rest vertex farthest from the supports (the centre of the fixed boxes):
/// the free end of a cantilever. Without supports, the vertex that moved farthest.
Vec3 tip_point(const FinalState& reference, const std::vector<AxisBox>& fixed);

}  // namespace corofem
