#include "fuzz_entries.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "scene/scene.hpp"

namespace corofem::fuzz {
namespace {

/// Writes the bytes to a per-process file with the given extension (gmsh reads by extension).
std::filesystem::path as_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("corofem-fuzz-" + std::to_string(::getpid()) + extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace

void scene_input(const std::uint8_t* data, std::size_t size) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(data, data + size);
  } catch (const nlohmann::json::exception&) {
    return;  // not JSON: load_scene reports it as bad input
  }
  try {
    parse_scene(json, "/nonexistent", "fuzz.json");
  } catch (const InputError&) {
  }
}

void msh_input(const std::uint8_t* data, std::size_t size) {
  const auto path = as_file(data, size, ".msh");
  try {
    read_volume_mesh(path);
  } catch (const InputError&) {
  }
  std::filesystem::remove(path);
}

void stl_input(const std::uint8_t* data, std::size_t size) {
  const auto path = as_file(data, size, ".stl");
  try {
    tetrahedralize_surface(path, 0.5);
  } catch (const InputError&) {
  }
  std::filesystem::remove(path);
}

}  // namespace corofem::fuzz
