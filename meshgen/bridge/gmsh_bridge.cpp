/// @file gmsh_bridge.cpp
/// libstagger_gmsh_bridge: the one object that links gmsh. libstagger_meshgen loads it on
/// first use (meshgen/src/gmsh_api.hpp), so that a process which never reads a .geo or .msh
/// file in itself never maps gmsh and its libraries.
#include "../src/gmsh_api.hpp"

extern "C" __attribute__((visibility("default"))) const stagger::meshgen::GmshApi* stagger_gmsh_bridge_api() {
  static const stagger::meshgen::GmshApi api{&gmsh::initialize,
                                             &gmsh::finalize,
                                             &gmsh::open,
                                             &gmsh::write,
                                             &gmsh::option::setNumber,
                                             &gmsh::option::getNumber,
                                             &gmsh::logger::start,
                                             &gmsh::logger::stop,
                                             &gmsh::logger::get,
                                             &gmsh::logger::getLastError,
                                             &gmsh::model::add,
                                             &gmsh::model::getEntities,
                                             &gmsh::model::setPhysicalName,
                                             &gmsh::model::getPhysicalGroups,
                                             &gmsh::model::getEntitiesForPhysicalGroup,
                                             &gmsh::model::addPhysicalGroup,
                                             &gmsh::model::addDiscreteEntity,
                                             &gmsh::model::getPhysicalName,
                                             &gmsh::model::getPartitions,
                                             &gmsh::model::getParent,
                                             &gmsh::model::getBoundary,
                                             &gmsh::model::getBoundingBox,
                                             &gmsh::model::mesh::clear,
                                             &gmsh::model::mesh::getElements,
                                             &gmsh::model::mesh::addElementsByType,
                                             &gmsh::model::mesh::refine,
                                             &gmsh::model::mesh::getNodes,
                                             &gmsh::model::mesh::getElementProperties,
                                             &gmsh::model::mesh::generate,
                                             &gmsh::model::mesh::addNodes};
  return &api;
}
