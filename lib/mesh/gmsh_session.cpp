#include "mesh/gmsh_session.hpp"

#include <set>
#include <unordered_map>

#include "mesh/gmsh_api.hpp"

namespace corofem {
namespace gmsh = gmsh_api;
namespace fs = std::filesystem;

namespace {

constexpr int kLinearTet = 4;  // gmsh element type of the 4-node tetrahedron

std::recursive_mutex& gmsh_turn() {
  static std::recursive_mutex turn;
  return turn;
}

}  // namespace

GmshSession::GmshSession() : turn_(gmsh_turn()) {
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.AbortOnError", 3);  // errors become exceptions
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (const std::exception&) {  // a destructor must not throw; the model is gone either way
  }
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

}  // namespace corofem
