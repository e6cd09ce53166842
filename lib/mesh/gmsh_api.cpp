#include "mesh/gmsh_api.hpp"

#include <dlfcn.h>

extern "C" {        // gmshc.h does not say it; its functions are C's
#include <gmshc.h>  // declarations only, never linked: their types check every call below
}

#include <mutex>
#include <stdexcept>

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

/// gmsh's C API reports failure in ierr; its message is in gmsh's log.
void check(int ierr, const char* function) {
  if (ierr == 0) return;
  std::string error;
  logger::getLastError(error);
  throw std::runtime_error(error.empty() ? std::string(function) + " failed" : error);
}

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
  int ierr = 0;
  GMSH_C(gmshInitialize)(0, nullptr, 0, &ierr);
  check(ierr, "gmshInitialize");
}

void finalize() {
  int ierr = 0;
  GMSH_C(gmshFinalize)(&ierr);
  check(ierr, "gmshFinalize");
}

void open(const std::string& file) {
  int ierr = 0;
  GMSH_C(gmshOpen)(file.c_str(), &ierr);
  check(ierr, "gmshOpen");
}

void merge(const std::string& file) {
  int ierr = 0;
  GMSH_C(gmshMerge)(file.c_str(), &ierr);
  check(ierr, "gmshMerge");
}

void option::setNumber(const std::string& name, double value) {
  int ierr = 0;
  GMSH_C(gmshOptionSetNumber)(name.c_str(), value, &ierr);
  check(ierr, "gmshOptionSetNumber");
}

void logger::getLastError(std::string& error) {
  char* message = nullptr;
  int ierr = 0;
  GMSH_C(gmshLoggerGetLastError)(&message, &ierr);
  error = message && ierr == 0 ? message : "";
  if (message) release(message);
}

void model::add(const std::string& name) {
  int ierr = 0;
  GMSH_C(gmshModelAdd)(name.c_str(), &ierr);
  check(ierr, "gmshModelAdd");
}

void model::getEntities(vectorpair& dim_tags, int dim) {
  int* data = nullptr;
  std::size_t n = 0;
  int ierr = 0;
  GMSH_C(gmshModelGetEntities)(&data, &n, dim, &ierr);
  check(ierr, "gmshModelGetEntities");
  dim_tags = pairs(data, n);
}

void model::getBoundingBox(int dim, int tag, double& xmin, double& ymin, double& zmin, double& xmax,
                           double& ymax, double& zmax) {
  int ierr = 0;
  GMSH_C(gmshModelGetBoundingBox)(dim, tag, &xmin, &ymin, &zmin, &xmax, &ymax, &zmax, &ierr);
  check(ierr, "gmshModelGetBoundingBox");
}

int model::addDiscreteEntity(int dim) {
  int ierr = 0;
  const int tag = GMSH_C(gmshModelAddDiscreteEntity)(dim, -1, nullptr, 0, &ierr);
  check(ierr, "gmshModelAddDiscreteEntity");
  return tag;
}

int model::geo::addSurfaceLoop(const std::vector<int>& surface_tags) {
  int ierr = 0;
  const int tag =
      GMSH_C(gmshModelGeoAddSurfaceLoop)(input(surface_tags), surface_tags.size(), -1, &ierr);
  check(ierr, "gmshModelGeoAddSurfaceLoop");
  return tag;
}

int model::geo::addVolume(const std::vector<int>& shell_tags) {
  int ierr = 0;
  const int tag = GMSH_C(gmshModelGeoAddVolume)(input(shell_tags), shell_tags.size(), -1, &ierr);
  check(ierr, "gmshModelGeoAddVolume");
  return tag;
}

void model::geo::synchronize() {
  int ierr = 0;
  GMSH_C(gmshModelGeoSynchronize)(&ierr);
  check(ierr, "gmshModelGeoSynchronize");
}

int model::occ::addBox(double x, double y, double z, double dx, double dy, double dz) {
  int ierr = 0;
  const int tag = GMSH_C(gmshModelOccAddBox)(x, y, z, dx, dy, dz, -1, &ierr);
  check(ierr, "gmshModelOccAddBox");
  return tag;
}

int model::occ::addCylinder(double x, double y, double z, double dx, double dy, double dz,
                            double r) {
  constexpr double kWhole = 6.283185307179586;  // the C++ API's default angle, 2 pi
  int ierr = 0;
  const int tag = GMSH_C(gmshModelOccAddCylinder)(x, y, z, dx, dy, dz, r, -1, kWhole, &ierr);
  check(ierr, "gmshModelOccAddCylinder");
  return tag;
}

void model::occ::fuse(const vectorpair& objects, const vectorpair& tools, vectorpair& out,
                      std::vector<vectorpair>& out_map) {
  std::vector<int> object_tags = flat(objects), tool_tags = flat(tools);
  int *out_data = nullptr, **map_data = nullptr;
  std::size_t out_n = 0, *map_sizes = nullptr, map_n = 0;
  int ierr = 0;
  GMSH_C(gmshModelOccFuse)
  (object_tags.data(), object_tags.size(), tool_tags.data(), tool_tags.size(), &out_data, &out_n,
   &map_data, &map_sizes, &map_n, -1, 1, 1, &ierr);
  check(ierr, "gmshModelOccFuse");
  out = pairs(out_data, out_n);
  out_map.clear();
  for (std::size_t i = 0; i < map_n; ++i) out_map.push_back(pairs(map_data[i], map_sizes[i]));
  release(map_data);
  release(map_sizes);
}

void model::occ::synchronize() {
  int ierr = 0;
  GMSH_C(gmshModelOccSynchronize)(&ierr);
  check(ierr, "gmshModelOccSynchronize");
}

void model::mesh::generate(int dim) {
  int ierr = 0;
  GMSH_C(gmshModelMeshGenerate)(dim, &ierr);
  check(ierr, "gmshModelMeshGenerate");
}

void model::mesh::getElements(std::vector<int>& types,
                              std::vector<std::vector<std::size_t>>& element_tags,
                              std::vector<std::vector<std::size_t>>& node_tags, int dim) {
  int* types_data = nullptr;
  std::size_t types_n = 0, **tags_data = nullptr, *tags_sizes = nullptr, tags_n = 0,
              **nodes_data = nullptr, *nodes_sizes = nullptr, nodes_n = 0;
  int ierr = 0;
  GMSH_C(gmshModelMeshGetElements)
  (&types_data, &types_n, &tags_data, &tags_sizes, &tags_n, &nodes_data, &nodes_sizes, &nodes_n,
   dim, -1, &ierr);
  check(ierr, "gmshModelMeshGetElements");
  types = take(types_data, types_n);
  element_tags = take_nested(tags_data, tags_sizes, tags_n);
  node_tags = take_nested(nodes_data, nodes_sizes, nodes_n);
}

void model::mesh::getNodes(std::vector<std::size_t>& node_tags, std::vector<double>& coords,
                           std::vector<double>& parametric, int dim, int tag, bool include_boundary,
                           bool return_parametric) {
  std::size_t *tags_data = nullptr, tags_n = 0, coords_n = 0, parametric_n = 0;
  double *coords_data = nullptr, *parametric_data = nullptr;
  int ierr = 0;
  GMSH_C(gmshModelMeshGetNodes)
  (&tags_data, &tags_n, &coords_data, &coords_n, &parametric_data, &parametric_n, dim, tag,
   include_boundary, return_parametric, &ierr);
  check(ierr, "gmshModelMeshGetNodes");
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
  int ierr = 0;
  GMSH_C(gmshModelMeshGetElementProperties)
  (type, &name_data, &dim, &order, &num_nodes, &local_data, &local_n, &num_primary_nodes, &ierr);
  check(ierr, "gmshModelMeshGetElementProperties");
  name = name_data ? name_data : "";
  if (name_data) release(name_data);
  local_coords = take(local_data, local_n);
}

void model::mesh::addNodes(int dim, int tag, const std::vector<std::size_t>& node_tags,
                           const std::vector<double>& coords) {
  int ierr = 0;
  GMSH_C(gmshModelMeshAddNodes)
  (dim, tag, input(node_tags), node_tags.size(), input(coords), coords.size(), nullptr, 0, &ierr);
  check(ierr, "gmshModelMeshAddNodes");
}

void model::mesh::addElementsByType(int tag, int type, const std::vector<std::size_t>& element_tags,
                                    const std::vector<std::size_t>& node_tags) {
  int ierr = 0;
  GMSH_C(gmshModelMeshAddElementsByType)
  (tag, type, input(element_tags), element_tags.size(), input(node_tags), node_tags.size(), &ierr);
  check(ierr, "gmshModelMeshAddElementsByType");
}

void model::mesh::getElementsByType(int type, std::vector<std::size_t>& element_tags,
                                    std::vector<std::size_t>& node_tags) {
  std::size_t *tags_data = nullptr, tags_n = 0, *nodes_data = nullptr, nodes_n = 0;
  int ierr = 0;
  GMSH_C(gmshModelMeshGetElementsByType)
  (type, &tags_data, &tags_n, &nodes_data, &nodes_n, -1, 0, 1, &ierr);
  check(ierr, "gmshModelMeshGetElementsByType");
  element_tags = take(tags_data, tags_n);
  node_tags = take(nodes_data, nodes_n);
}

}  // namespace corofem::gmsh_api
