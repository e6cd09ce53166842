#pragma once
// Matrix Market "coordinate real general" files (1-based), for checks in other tools.
#include <Eigen/SparseCore>
#include <filesystem>

namespace corofem {

/// Writes every stored entry of `m` (explicit zeros of BRC blocks included), atomically.
void write_matrix_market(const std::filesystem::path& file, const Eigen::SparseMatrix<double>& m);

/// Reads a coordinate real general file (tests and round trips). Throws InputError naming the file.
Eigen::SparseMatrix<double> read_matrix_market(const std::filesystem::path& file);

}  // namespace corofem
