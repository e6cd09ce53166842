#include "scene/scene_paths.hpp"

namespace corofem {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void move_path(json& holder, const char* key, const fs::path& from, const fs::path& to) {
  if (!holder.is_object() || !holder.contains(key) || !holder[key].is_string()) return;
  const fs::path path = holder[key].get<std::string>();
  if (path.is_absolute()) return;
  holder[key] = fs::relative(fs::absolute(from / path), fs::absolute(to)).generic_string();
}

}  // namespace

json with_paths_moved(json scene, const fs::path& from_dir, const fs::path& to_dir) {
  if (scene.contains("mesh")) {
    json& mesh = scene["mesh"];
    for (const char* key : {"file", "surface"}) move_path(mesh, key, from_dir, to_dir);
    if (mesh.is_object() && mesh.contains("levels") && mesh["levels"].is_array())
      for (json& level : mesh["levels"])
        for (const char* key : {"file", "surface"}) move_path(level, key, from_dir, to_dir);
  }
  if (scene.contains("output")) move_path(scene["output"], "vtu", from_dir, to_dir);
  return scene;
}

}  // namespace corofem
