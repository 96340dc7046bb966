#pragma once
// Boundary conditions checked against the geometry they land on (docs/robustness.md): before
// any array is built, by Problem::validate and, with the file and line, by the scene reader.
#include <cstddef>
#include <optional>
#include <string>

#include "stagger/problem.hpp"

namespace stagger {

// What is wrong with one boundary condition on the mesh it lands on.
struct BoundaryGeometryProblem {
  std::size_t boundary = 0;  // index into Problem::boundaries
  std::string message;       // "boundary 'tag' (type ...): ...; what to do"
};

// The first boundary condition of `problem` that cannot hold where it lands, if any: a tag
// with interior edges (shared by two zones); in rz (numerics.geometry = "rz") a velocity or
// pressure condition with edges on the axis x = 0, or a periodic pair that is not an axial
// translation (the axis or any radial translation).
std::optional<BoundaryGeometryProblem> boundary_geometry_problem(const Problem& problem);

// The scene's word for a boundary kind ("wall", "velocity", ...: the `type` key).
const char* boundary_kind_name(BoundaryKind kind);

// Points within this distance of x = 0 are on the rz axis (the set-up puts them on it).
double axis_tolerance(const Mesh& mesh);

}  // namespace stagger
