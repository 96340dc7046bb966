#pragma once
/// @file soup_extraction.hpp
/// The current gmsh model as a polygon soup (docs/mesh.md): physical surfaces become regions,
/// physical curves tags. Called inside a gmsh session (gmsh_session.hpp), after gmsh read or
/// meshed the file.
#include <string>

#include "stagger/mesh.hpp"

namespace stagger::meshgen {

/// A 2D code needs a 2D model: volumes are refused up front (a 3D model's surfaces would
/// otherwise be projected onto z = 0 and collapse into "duplicate points"). A .msh may list
/// the volume entities of the model it came from: there only volume elements count.
void require_planar_model(const std::string& path, bool volume_entities_count);

/// The current gmsh model's physical surfaces and curves as a polygon soup; `path` names the
/// file in the soup and in errors.
PolygonSoup extract_soup(const std::string& path);

}  // namespace stagger::meshgen
