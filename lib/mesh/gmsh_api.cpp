#include "mesh/gmsh_api.hpp"

#include <dlfcn.h>

extern "C" {        // gmshc.h does not say it; its functions are C's
#include <gmshc.h>  // declarations only, never linked: their types check every call below
}

#include <mutex>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace corofem::gmsh_api {

namespace {

void* library() {
  static void* handle = nullptr;
  static std::string why;  // dlerror() of the one attempt
  static std::once_flag loaded;
  std::call_once(loaded, [] {
    handle = dlopen(COROFEM_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!handle) why = dlerror();
  });
  if (!handle)
    throw std::runtime_error(std::string("gmsh's library ") + COROFEM_GMSH_LIBRARY +
                             " could not be loaded: " + why);
  return handle;
}

template <class F>
F* resolve(const char* name) {
  void* symbol = dlsym(library(), name);
  if (!symbol)
    throw std::runtime_error(std::string("gmsh's library ") + COROFEM_GMSH_LIBRARY + " has no " +
                             name);
  return reinterpret_cast<F*>(symbol);
}

// The C function of that name, resolved in gmsh's library, with gmshc.h's type.
#define GMSH_C(name) (resolve<decltype(::name)>(#name))

void release(void* p) {
  GMSH_C(gmshFree)(p);
}

/// gmsh's last logged error ("" when there is none or it cannot be read).
std::string last_error() {
  char* message = nullptr;
  int ierr = 0;
  GMSH_C(gmshLoggerGetLastError)(&message, &ierr);
  std::string error = message && ierr == 0 ? message : "";
  if (message) release(message);
  return error;
}

/// Calls gmsh's C function F (named `name`) with `args` and its ierr, and returns its result;
/// gmsh's C API reports failure in ierr, with its message in gmsh's log.
template <class F, class... Args>
auto call(const char* name, Args&&... args) {
  F* function = resolve<F>(name);
  int ierr = 0;
  const auto checked = [&] {
    if (ierr == 0) return;
    const std::string error = last_error();
    throw std::runtime_error(error.empty() ? std::string(name) + " failed" : error);
  };
  if constexpr (std::is_void_v<std::invoke_result_t<F*, Args..., int*>>) {
    function(std::forward<Args>(args)..., &ierr);
    checked();
  } else {
    const auto result = function(std::forward<Args>(args)..., &ierr);
    checked();
    return result;
  }
}

// Calls the C function of that name (gmshc.h) with these arguments and its ierr, checked.
#define GMSH_CALL(name, ...) (call<decltype(::name)>(#name __VA_OPT__(, ) __VA_ARGS__))

template <class T>
std::vector<T> take(T* data, std::size_t n) {
  std::vector<T> v(data, data + n);
  release(data);
  return v;
}

vectorpair pairs(int* dim_tags, std::size_t n) {
  vectorpair v;
  for (std::size_t i = 0; i + 1 < n; i += 2) v.emplace_back(dim_tags[i], dim_tags[i + 1]);
  release(dim_tags);
  return v;
}

std::vector<int> flat(const vectorpair& dim_tags) {
  std::vector<int> v;
  for (const auto& [dim, tag] : dim_tags) v.insert(v.end(), {dim, tag});
  return v;
}

template <class T>
std::vector<std::vector<T>> take_nested(T** data, std::size_t* sizes, std::size_t n) {
  std::vector<std::vector<T>> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back(take(data[i], sizes[i]));
  release(data);
  release(sizes);
  return v;
}

template <class T>
T* input(const std::vector<T>& v) {  // the C API's inputs are not const-qualified
  return const_cast<T*>(v.data());
}

}  // namespace

void initialize() {
  GMSH_CALL(gmshInitialize, 0, nullptr, 0);
}

void finalize() {
  GMSH_CALL(gmshFinalize);
}

void open(const std::string& file) {
  GMSH_CALL(gmshOpen, file.c_str());
}

void merge(const std::string& file) {
  GMSH_CALL(gmshMerge, file.c_str());
}

void option::setNumber(const std::string& name, double value) {
  GMSH_CALL(gmshOptionSetNumber, name.c_str(), value);
}

void model::add(const std::string& name) {
  GMSH_CALL(gmshModelAdd, name.c_str());
}

void model::getEntities(vectorpair& dim_tags, int dim) {
  int* data = nullptr;
  std::size_t n = 0;
  GMSH_CALL(gmshModelGetEntities, &data, &n, dim);
  dim_tags = pairs(data, n);
}

void model::getBoundingBox(int dim, int tag, double& xmin, double& ymin, double& zmin, double& xmax,
                           double& ymax, double& zmax) {
  GMSH_CALL(gmshModelGetBoundingBox, dim, tag, &xmin, &ymin, &zmin, &xmax, &ymax, &zmax);
}

int model::addDiscreteEntity(int dim) {
  return GMSH_CALL(gmshModelAddDiscreteEntity, dim, -1, nullptr, 0);
}

int model::geo::addSurfaceLoop(const std::vector<int>& surface_tags) {
  return GMSH_CALL(gmshModelGeoAddSurfaceLoop, input(surface_tags), surface_tags.size(), -1);
}

int model::geo::addVolume(const std::vector<int>& shell_tags) {
  return GMSH_CALL(gmshModelGeoAddVolume, input(shell_tags), shell_tags.size(), -1);
}

void model::geo::synchronize() {
  GMSH_CALL(gmshModelGeoSynchronize);
}

int model::occ::addBox(double x, double y, double z, double dx, double dy, double dz) {
  return GMSH_CALL(gmshModelOccAddBox, x, y, z, dx, dy, dz, -1);
}

int model::occ::addCylinder(double x, double y, double z, double dx, double dy, double dz,
                            double r) {
  constexpr double kWhole = 6.283185307179586;  // the C++ API's default angle, 2 pi
  return GMSH_CALL(gmshModelOccAddCylinder, x, y, z, dx, dy, dz, r, -1, kWhole);
}

void model::occ::fuse(const vectorpair& objects, const vectorpair& tools, vectorpair& out,
                      std::vector<vectorpair>& out_map) {
  std::vector<int> object_tags = flat(objects), tool_tags = flat(tools);
  int *out_data = nullptr, **map_data = nullptr;
  std::size_t out_n = 0, *map_sizes = nullptr, map_n = 0;
  GMSH_CALL(gmshModelOccFuse, object_tags.data(), object_tags.size(), tool_tags.data(),
            tool_tags.size(), &out_data, &out_n, &map_data, &map_sizes, &map_n, -1, 1, 1);
  out = pairs(out_data, out_n);
  out_map.clear();
  for (std::size_t i = 0; i < map_n; ++i) out_map.push_back(pairs(map_data[i], map_sizes[i]));
  release(map_data);
  release(map_sizes);
}

void model::occ::synchronize() {
  GMSH_CALL(gmshModelOccSynchronize);
}

void model::mesh::generate(int dim) {
  GMSH_CALL(gmshModelMeshGenerate, dim);
}

void model::mesh::getElements(std::vector<int>& types,
                              std::vector<std::vector<std::size_t>>& element_tags,
                              std::vector<std::vector<std::size_t>>& node_tags, int dim) {
  int* types_data = nullptr;
  std::size_t types_n = 0, **tags_data = nullptr, *tags_sizes = nullptr, tags_n = 0,
              **nodes_data = nullptr, *nodes_sizes = nullptr, nodes_n = 0;
  GMSH_CALL(gmshModelMeshGetElements, &types_data, &types_n, &tags_data, &tags_sizes, &tags_n,
            &nodes_data, &nodes_sizes, &nodes_n, dim, -1);
  types = take(types_data, types_n);
  element_tags = take_nested(tags_data, tags_sizes, tags_n);
  node_tags = take_nested(nodes_data, nodes_sizes, nodes_n);
}

void model::mesh::getNodes(std::vector<std::size_t>& node_tags, std::vector<double>& coords,
                           std::vector<double>& parametric, int dim, int tag, bool include_boundary,
                           bool return_parametric) {
  std::size_t *tags_data = nullptr, tags_n = 0, coords_n = 0, parametric_n = 0;
  double *coords_data = nullptr, *parametric_data = nullptr;
  GMSH_CALL(gmshModelMeshGetNodes, &tags_data, &tags_n, &coords_data, &coords_n, &parametric_data,
            &parametric_n, dim, tag, include_boundary, return_parametric);
  node_tags = take(tags_data, tags_n);
  coords = take(coords_data, coords_n);
  parametric = take(parametric_data, parametric_n);
}

void model::mesh::getElementProperties(int type, std::string& name, int& dim, int& order,
                                       int& num_nodes, std::vector<double>& local_coords,
                                       int& num_primary_nodes) {
  char* name_data = nullptr;
  double* local_data = nullptr;
  std::size_t local_n = 0;
  GMSH_CALL(gmshModelMeshGetElementProperties, type, &name_data, &dim, &order, &num_nodes,
            &local_data, &local_n, &num_primary_nodes);
  name = name_data ? name_data : "";
  if (name_data) release(name_data);
  local_coords = take(local_data, local_n);
}

void model::mesh::addNodes(int dim, int tag, const std::vector<std::size_t>& node_tags,
                           const std::vector<double>& coords) {
  GMSH_CALL(gmshModelMeshAddNodes, dim, tag, input(node_tags), node_tags.size(), input(coords),
            coords.size(), nullptr, 0);
}

void model::mesh::addElementsByType(int tag, int type, const std::vector<std::size_t>& element_tags,
                                    const std::vector<std::size_t>& node_tags) {
  GMSH_CALL(gmshModelMeshAddElementsByType, tag, type, input(element_tags), element_tags.size(),
            input(node_tags), node_tags.size());
}

void model::mesh::getElementsByType(int type, std::vector<std::size_t>& element_tags,
                                    std::vector<std::size_t>& node_tags) {
  std::size_t *tags_data = nullptr, tags_n = 0, *nodes_data = nullptr, nodes_n = 0;
  GMSH_CALL(gmshModelMeshGetElementsByType, type, &tags_data, &tags_n, &nodes_data, &nodes_n, -1, 0,
            1);
  element_tags = take(tags_data, tags_n);
  node_tags = take(nodes_data, nodes_n);
}

}  // namespace corofem::gmsh_api
