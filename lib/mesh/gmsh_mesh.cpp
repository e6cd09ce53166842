#include "mesh/gmsh_mesh.hpp"

#include <gmsh.h>

#include <fstream>
#include <set>
#include <unordered_map>

#include "core/errors.hpp"
#include "mesh/msh_precheck.hpp"

namespace corofem {
namespace fs = std::filesystem;

namespace {

constexpr int kLinearTet = 4;  // gmsh element type of the 4-node tetrahedron

/// One gmsh API session; gmsh keeps global state, so each read gets a clean one.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.AbortOnError", 3);  // errors become exceptions
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

std::string last_gmsh_error() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
  }
  return error.empty() ? "unknown gmsh error" : error;
}

/// Runs a gmsh call and turns whatever gmsh throws (it throws strings and ints, not only
/// std::exception) into an InputError naming the file.
template <class F>
void call_gmsh(const fs::path& file, const char* what, F&& f) {
  try {
    f();
  } catch (const InputError&) {
    throw;
  } catch (const std::string& message) {
    throw InputError("gmsh could not " + std::string(what) + " '" + file.string() + "': " + message);
  } catch (const std::exception& e) {
    throw InputError("gmsh could not " + std::string(what) + " '" + file.string() + "': " + e.what());
  } catch (...) {
    throw InputError("gmsh could not " + std::string(what) + " '" + file.string() +
                     "': " + last_gmsh_error());
  }
}

void check_readable(const fs::path& file) {
  // gmsh's open on a missing file only logs; check first.
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError("mesh file '" + file.string() + "' does not exist");
  if (!fs::is_regular_file(file, ec))
    throw InputError("mesh file '" + file.string() + "' is not a regular file");
  std::ifstream probe(file, std::ios::binary);
  if (!probe) throw InputError("mesh file '" + file.string() + "' cannot be read");
  if (probe.peek() == std::ifstream::traits_type::eof())
    throw InputError("mesh file '" + file.string() + "' is empty");
}

/// Collects the current gmsh model's linear tets and the nodes they use.
TetMesh collect_tets(const fs::path& file) {
  TetMesh mesh;
  mesh.source = file.string();
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  call_gmsh(file, "read the mesh of", [&] {
    gmsh::model::mesh::getElements(types, element_tags, element_nodes, 3);
    gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  });
  std::set<std::string> other_types;
  for (std::size_t t = 0; t < types.size(); ++t) {
    if (types[t] == kLinearTet) continue;
    std::string name;
    int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
    std::vector<double> local;
    call_gmsh(file, "describe an element type of", [&] {
      gmsh::model::mesh::getElementProperties(types[t], name, dim, order, num_nodes, local,
                                              num_primary);
    });
    other_types.insert(name + " (gmsh type " + std::to_string(types[t]) + ", " +
                       std::to_string(element_tags[t].size()) + " elements)");
  }
  if (!other_types.empty()) {
    std::string list;
    for (const auto& s : other_types) list += (list.empty() ? "" : ", ") + s;
    throw InputError("mesh '" + file.string() + "' has volume elements that are not linear tets: " +
                     list + "; corofem needs 4-node tetrahedra");
  }
  std::unordered_map<std::size_t, int> index_of;
  index_of.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    index_of.emplace(node_tags[i], static_cast<int>(i));
    mesh.rest.emplace_back(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
  }
  mesh.node_tags = node_tags;
  for (std::size_t t = 0; t < types.size(); ++t) {
    for (std::size_t e = 0; e < element_tags[t].size(); ++e) {
      Tet tet;
      for (int a = 0; a < 4; ++a) {
        auto it = index_of.find(element_nodes[t][4 * e + a]);
        if (it == index_of.end())
          throw InputError("element " + std::to_string(element_tags[t][e]) + " of '" +
                           file.string() + "' refers to node " +
                           std::to_string(element_nodes[t][4 * e + a]) + ", which does not exist");
        tet[a] = it->second;
      }
      mesh.tets.push_back(tet);
      mesh.element_tags.push_back(element_tags[t][e]);
    }
  }
  validate_mesh(mesh);
  return mesh;
}

}  // namespace

TetMesh read_volume_mesh(const fs::path& file) {
  check_readable(file);
  precheck_msh(file);
  GmshSession session;
  call_gmsh(file, "open", [&] { gmsh::open(file.string()); });
  return collect_tets(file);
}

TetMesh tetrahedralize_surface(const fs::path& file, double size) {
  check_readable(file);
  precheck_stl(file);
  if (!(size > 0) || !std::isfinite(size))
    throw InputError("mesh size for '" + file.string() + "' must be a positive number");
  GmshSession session;
  call_gmsh(file, "tetrahedralize", [&] {
    gmsh::merge(file.string());
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    if (surfaces.empty()) throw InputError("surface file '" + file.string() + "' has no triangles");
    std::vector<int> surface_tags;
    for (const auto& dt : surfaces) surface_tags.push_back(dt.second);
    int loop = gmsh::model::geo::addSurfaceLoop(surface_tags);
    gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::model::mesh::generate(3);
  });
  return collect_tets(file);
}

}  // namespace corofem
