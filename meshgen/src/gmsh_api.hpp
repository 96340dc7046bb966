/// @file gmsh_api.hpp
/// The gmsh 4.8 C++ API functions stagger uses, reached through a small module,
/// libstagger_gmsh_bridge, that links gmsh and is loaded on first use (docs/mesh.md, "gmsh in
/// a child process"). A run reads and meshes in a forked child, so only that child loads gmsh
/// and its libraries (OpenCASCADE, FLTK: about 38 MiB of a process's resident set): the
/// stagger process itself, and every rank of a distributed run, never does
/// (docs/parallel.md, "Memory"). `gm::` below mirrors the `gmsh::` functions, defaults included.
#pragma once
#include <gmsh.h>

#include <string>
#include <vector>

namespace stagger::meshgen {

struct GmshApi {
  decltype(&gmsh::initialize) initialize;
  decltype(&gmsh::finalize) finalize;
  decltype(&gmsh::open) open;
  decltype(&gmsh::write) write;
  decltype(&gmsh::option::setNumber) option_set_number;
  decltype(&gmsh::option::getNumber) option_get_number;
  decltype(&gmsh::logger::start) logger_start;
  decltype(&gmsh::logger::stop) logger_stop;
  decltype(&gmsh::logger::get) logger_get;
  decltype(&gmsh::logger::getLastError) logger_get_last_error;
  decltype(&gmsh::model::add) model_add;
  decltype(&gmsh::model::getEntities) get_entities;
  decltype(&gmsh::model::setPhysicalName) set_physical_name;
  decltype(&gmsh::model::getPhysicalGroups) get_physical_groups;
  decltype(&gmsh::model::getEntitiesForPhysicalGroup) get_entities_for_physical_group;
  decltype(&gmsh::model::addPhysicalGroup) add_physical_group;
  decltype(&gmsh::model::addDiscreteEntity) add_discrete_entity;
  decltype(&gmsh::model::getPhysicalName) get_physical_name;
  decltype(&gmsh::model::getPartitions) get_partitions;
  decltype(&gmsh::model::getParent) get_parent;
  decltype(&gmsh::model::getBoundary) get_boundary;
  decltype(&gmsh::model::getBoundingBox) get_bounding_box;
  decltype(&gmsh::model::mesh::clear) mesh_clear;
  decltype(&gmsh::model::mesh::getElements) get_elements;
  decltype(&gmsh::model::mesh::addElementsByType) add_elements_by_type;
  decltype(&gmsh::model::mesh::refine) refine;
  decltype(&gmsh::model::mesh::getNodes) get_nodes;
  decltype(&gmsh::model::mesh::getElementProperties) get_element_properties;
  decltype(&gmsh::model::mesh::generate) generate;
  decltype(&gmsh::model::mesh::addNodes) add_nodes;
};

/// Loads the bridge (and with it gmsh) on the first call; throws stagger::Error if it cannot.
const GmshApi& gmsh_api();

namespace gm {
inline void initialize(int argc = 0, char** argv = nullptr, const bool readConfigFiles = true) {
  gmsh_api().initialize(argc, argv, readConfigFiles);
}
inline void finalize() {
  gmsh_api().finalize();
}
inline void open(const std::string& fileName) {
  gmsh_api().open(fileName);
}
inline void write(const std::string& fileName) {
  gmsh_api().write(fileName);
}
namespace option {
inline void setNumber(const std::string& name, const double value) {
  gmsh_api().option_set_number(name, value);
}
inline void getNumber(const std::string& name, double& value) {
  gmsh_api().option_get_number(name, value);
}
}  // namespace option
namespace logger {
inline void start() {
  gmsh_api().logger_start();
}
inline void stop() {
  gmsh_api().logger_stop();
}
inline void get(std::vector<std::string>& log) {
  gmsh_api().logger_get(log);
}
inline void getLastError(std::string& error) {
  gmsh_api().logger_get_last_error(error);
}
}  // namespace logger
namespace model {
inline void add(const std::string& name) {
  gmsh_api().model_add(name);
}
inline void getEntities(gmsh::vectorpair& dimTags, const int dim = -1) {
  gmsh_api().get_entities(dimTags, dim);
}
inline void setPhysicalName(const int dim, const int tag, const std::string& name) {
  gmsh_api().set_physical_name(dim, tag, name);
}
inline void getPhysicalGroups(gmsh::vectorpair& dimTags, const int dim = -1) {
  gmsh_api().get_physical_groups(dimTags, dim);
}
inline void getEntitiesForPhysicalGroup(const int dim, const int tag, std::vector<int>& tags) {
  gmsh_api().get_entities_for_physical_group(dim, tag, tags);
}
inline int addPhysicalGroup(const int dim, const std::vector<int>& tags, const int tag = -1) {
  return gmsh_api().add_physical_group(dim, tags, tag);
}
inline int addDiscreteEntity(const int dim, const int tag = -1, const std::vector<int>& boundary = {}) {
  return gmsh_api().add_discrete_entity(dim, tag, boundary);
}
inline void getPhysicalName(const int dim, const int tag, std::string& name) {
  gmsh_api().get_physical_name(dim, tag, name);
}
inline void getPartitions(const int dim, const int tag, std::vector<int>& partitions) {
  gmsh_api().get_partitions(dim, tag, partitions);
}
inline void getParent(const int dim, const int tag, int& parentDim, int& parentTag) {
  gmsh_api().get_parent(dim, tag, parentDim, parentTag);
}
inline void getBoundary(const gmsh::vectorpair& dimTags, gmsh::vectorpair& outDimTags, const bool combined = true,
                        const bool oriented = true, const bool recursive = false) {
  gmsh_api().get_boundary(dimTags, outDimTags, combined, oriented, recursive);
}
inline void getBoundingBox(const int dim, const int tag, double& xmin, double& ymin, double& zmin, double& xmax,
                           double& ymax, double& zmax) {
  gmsh_api().get_bounding_box(dim, tag, xmin, ymin, zmin, xmax, ymax, zmax);
}
namespace mesh {
inline void clear(const gmsh::vectorpair& dimTags = gmsh::vectorpair()) {
  gmsh_api().mesh_clear(dimTags);
}
inline void getElements(std::vector<int>& elementTypes, std::vector<std::vector<std::size_t>>& elementTags,
                        std::vector<std::vector<std::size_t>>& nodeTags, const int dim = -1, const int tag = -1) {
  gmsh_api().get_elements(elementTypes, elementTags, nodeTags, dim, tag);
}
inline void addElementsByType(const int tag, const int elementType, const std::vector<std::size_t>& elementTags,
                              const std::vector<std::size_t>& nodeTags) {
  gmsh_api().add_elements_by_type(tag, elementType, elementTags, nodeTags);
}
inline void refine() {
  gmsh_api().refine();
}
inline void getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
                     std::vector<double>& parametricCoord, const int dim = -1, const int tag = -1,
                     const bool includeBoundary = false, const bool returnParametricCoord = true) {
  gmsh_api().get_nodes(nodeTags, coord, parametricCoord, dim, tag, includeBoundary, returnParametricCoord);
}
inline void getElementProperties(const int elementType, std::string& elementName, int& dim, int& order, int& numNodes,
                                 std::vector<double>& localNodeCoord, int& numPrimaryNodes) {
  gmsh_api().get_element_properties(elementType, elementName, dim, order, numNodes, localNodeCoord, numPrimaryNodes);
}
inline void generate(const int dim = 3) {
  gmsh_api().generate(dim);
}
inline void addNodes(const int dim, const int tag, const std::vector<std::size_t>& nodeTags,
                     const std::vector<double>& coord, const std::vector<double>& parametricCoord = {}) {
  gmsh_api().add_nodes(dim, tag, nodeTags, coord, parametricCoord);
}
}  // namespace mesh
}  // namespace model
}  // namespace gm

}  // namespace stagger::meshgen
