#pragma once
// The part of gmsh's API corofem uses, with gmsh.h's names and arguments, over gmsh's C API
// (gmshc.h) loaded at the first call (dlopen). A run that never meshes maps none of gmsh's
// libraries: linked, they cost every process 42 MB of resident memory and 0.27 s of start-up
// (OpenCASCADE's among them), once per rank under mpirun, where only rank 0 meshes.
// Each call throws std::runtime_error with gmsh's last logged error when gmsh reports one, or
// when gmsh cannot be loaded (the message names the library).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace corofem::gmsh_api {

using vectorpair = std::vector<std::pair<int, int>>;

void initialize();  // no arguments, no configuration files read
void finalize();
void open(const std::string& file);
void merge(const std::string& file);

namespace option {
void setNumber(const std::string& name, double value);
}  // namespace option

namespace model {
void add(const std::string& name);
void getEntities(vectorpair& dim_tags, int dim);
void getBoundingBox(int dim, int tag, double& xmin, double& ymin, double& zmin, double& xmax,
                    double& ymax, double& zmax);
int addDiscreteEntity(int dim);

namespace geo {
int addSurfaceLoop(const std::vector<int>& surface_tags);
int addVolume(const std::vector<int>& shell_tags);
void synchronize();
}  // namespace geo

namespace occ {
int addBox(double x, double y, double z, double dx, double dy, double dz);
int addCylinder(double x, double y, double z, double dx, double dy, double dz, double r);
void fuse(const vectorpair& objects, const vectorpair& tools, vectorpair& out,
          std::vector<vectorpair>& out_map);
void synchronize();
}  // namespace occ

namespace mesh {
void generate(int dim);
void getElements(std::vector<int>& types, std::vector<std::vector<std::size_t>>& element_tags,
                 std::vector<std::vector<std::size_t>>& node_tags, int dim);
void getNodes(std::vector<std::size_t>& node_tags, std::vector<double>& coords,
              std::vector<double>& parametric, int dim, int tag, bool include_boundary,
              bool return_parametric);
void getElementProperties(int type, std::string& name, int& dim, int& order, int& num_nodes,
                          std::vector<double>& local_coords, int& num_primary_nodes);
void addNodes(int dim, int tag, const std::vector<std::size_t>& node_tags,
              const std::vector<double>& coords);
void addElementsByType(int tag, int type, const std::vector<std::size_t>& element_tags,
                       const std::vector<std::size_t>& node_tags);
void getElementsByType(int type, std::vector<std::size_t>& element_tags,
                       std::vector<std::size_t>& node_tags);
}  // namespace mesh
}  // namespace model

}  // namespace corofem::gmsh_api
