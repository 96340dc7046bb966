#pragma once
/// @file child_protocol.hpp
/// What the gmsh child sends back through its pipe (docs/mesh.md, "gmsh in a child
/// process"): one byte, 0 for a soup or 1 for an error, then the soup's arrays or the error's
/// one line.
#include <string>

#include "stagger/mesh.hpp"

namespace stagger::meshgen {

/// The answer that carries `soup`.
std::string pack(const PolygonSoup& soup);
/// The answer that carries an error message.
std::string pack_failure(const std::string& message);
/// The soup of an answer; throws stagger::Error with the message of an error answer, and
/// std::runtime_error if the bytes are truncated or longer than the answer.
PolygonSoup unpack(const std::string& bytes);

}  // namespace stagger::meshgen
