#pragma once
/// @file geo_scanner.hpp
/// The scan of a .geo file and what it includes or merges (geo_scanner.cpp).
#include <string>

namespace stagger::meshgen {

/// The first command of `path` (or of a file it includes) that reaches outside the mesh, as
/// "FILE:LINE: what", or "" (only when `refuse_commands`: allowed files are scanned for the
/// rest alone). Throws stagger::Error "FILE:LINE: ..." for an Include or Merge of a file that
/// is not a regular file, an include cycle, a merged .msh that gmsh would run as a script
/// (check_msh_file), and files beyond the scan's size limits (16 MiB a file, 64 MiB in all).
std::string scan_geo(const std::string& path, bool refuse_commands);

}  // namespace stagger::meshgen
