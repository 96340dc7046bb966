#pragma once
/// @file triangle_policy.hpp
/// What happens to triangles left in a soup (TrianglePolicy): counting them, the all-quad
/// subdivision of a soup, and the 'reject' check.
#include <cstddef>

#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {

/// Number of 3-point polygons of `soup`.
std::size_t count_triangles(const PolygonSoup& soup);

/// All-quad subdivision of a soup, the same as gmsh's (Mesh.SubdivisionAlgorithm = 1): an
/// n-gon becomes n quads around its centroid through its edge midpoints (a triangle 3, a
/// quad 4). Only if there are triangles. A tagged edge is split at its midpoint.
void subdivide_soup(PolygonSoup& soup);

/// Under TrianglePolicy::reject, throws stagger::Error if `soup` has triangles.
void apply_policy(const PolygonSoup& soup, TrianglePolicy policy);

}  // namespace stagger::meshgen
