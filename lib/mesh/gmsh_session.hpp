#pragma once
// What every use of the gmsh API shares: a clean session per model, gmsh's exceptions turned into
// InputError, and the model's linear tets collected into a TetMesh.
#include <filesystem>
#include <mutex>
#include <string>

#include "core/errors.hpp"
#include "mesh/tet_mesh.hpp"

namespace corofem {

/// One gmsh API session; gmsh keeps global state, so each model gets a clean one, and sessions in
/// threads running side by side (the stability study's runs) take turns.
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  std::unique_lock<std::recursive_mutex> turn_;
};

/// Runs gmsh calls and turns what they throw (std::runtime_error with gmsh's message,
/// mesh/gmsh_api.hpp) into an InputError naming `source`.
template <class F>
void call_gmsh(const std::filesystem::path& source, const char* what, F&& f) {
  try {
    f();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError("gmsh could not " + std::string(what) + " '" + source.string() +
                     "': " + e.what());
  }
}

/// Collects the current gmsh model's linear tets and the nodes they use (validated; tags kept).
/// Throws InputError naming `source` for volume elements that are not linear tets.
TetMesh collect_tets(const std::filesystem::path& source);

}  // namespace corofem
