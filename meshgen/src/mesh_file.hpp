#pragma once
/// @file mesh_file.hpp
/// What the file readers (read_geo, read_msh, read_mesh_file) check first.
#include <string>

namespace stagger::meshgen {

/// Throws stagger::Error unless `path` is a regular file; `what` names it ("mesh file").
void require_file(const std::string& path, const std::string& what);

}  // namespace stagger::meshgen
