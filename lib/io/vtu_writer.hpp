#pragma once
// VTK XML unstructured grid (.vtu, ASCII) for ParaView: rest points, point data "displacement"
// (apply Warp By Vector to see the deformed shape), cell data "rotation_angle" (rad).
#include <filesystem>
#include <string>
#include <vector>

#include "element/element_stiffness.hpp"

namespace corofem {

void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const Eigen::VectorXd& displacement, const std::vector<Mat3>& rotations);

/// A parallel VTU: `file` (.pvtu) naming the pieces `pieces` (file names beside it), each a .vtu
/// as write_vtu writes them (one per rank of a distributed run). ParaView opens `file`.
void write_pvtu(const std::filesystem::path& file, const std::vector<std::string>& pieces);

/// Angle (rad) of a rotation; of -Q for a reflection.
double rotation_angle(const Mat3& q);

}  // namespace corofem
