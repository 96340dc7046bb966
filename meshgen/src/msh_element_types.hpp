#pragma once
/// @file msh_element_types.hpp
/// The MSH element types stagger reads and writes (gmsh reference manual, "MSH file format").

namespace stagger::meshgen {

constexpr int kLine2 = 1, kTriangle3 = 2, kQuad4 = 3;

}  // namespace stagger::meshgen
