#pragma once
// `corofem export-matrices`: every level's system matrix and transfer operator of a scene.
#include <filesystem>

#include "scene/scene.hpp"

namespace corofem {

/// Runs the scene's first linear solve (static: the first iteration of the first increment;
/// dynamic: the first step) through the multigrid hierarchy of its `levels`, and writes
/// A<h>.mtx (3 n_h square), R<h>.mtx (3 n_{h+1} x 3 n_h, level h to h+1) and levels.json to `dir`.
/// DOF index 3 vertex + component. A<h+1> is exactly the product the solver used.
void export_matrices(const Scene& scene, const std::filesystem::path& dir);

}  // namespace corofem
