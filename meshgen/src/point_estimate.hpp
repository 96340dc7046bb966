#pragma once
/// @file point_estimate.hpp
/// An estimate of a .geo mesh's size before its surfaces are meshed (docs/mesh.md, "Mesh
/// size estimate"): a mesh size asking for 1e9 points used to mesh for minutes, then run out
/// of memory or time, with no word of why.
#include <string>

namespace stagger::meshgen {

/// In a gmsh session with the .geo open: meshes its curves (cheap: a boundary of a mesh of
/// 1e9 points has about 1e5) and throws stagger::Error naming `path` if the surfaces' mesh
/// would have more than `limit` points. The estimate is each surface's area over the square
/// of its longest boundary segment, a lower bound where sizes extend from the boundary
/// (gmsh's default); with Mesh.MeshSizeExtendFromBoundary = 0 (sizes from fields alone)
/// nothing is estimated.
void check_point_estimate(const std::string& path, double limit);

}  // namespace stagger::meshgen
