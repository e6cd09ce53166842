#pragma once
// A scene JSON moved to another folder: its relative paths (mesh files and surfaces, of every
// level, and output.vtu) rewritten so that they still name the same files.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace corofem {

/// `scene`, read from `from_dir`, as it must be written into `to_dir`.
nlohmann::json with_paths_moved(nlohmann::json scene, const std::filesystem::path& from_dir,
                                const std::filesystem::path& to_dir);

}  // namespace corofem
