#pragma once
// The hydro tests' problems: the shared gas builders (tests/support/gas_problem.hpp) and a
// perturbed mesh.
#include <vector>

#include "stagger/mesh.hpp"
#include "support/gas_problem.hpp"

namespace stagger::testing {

// Moves interior points by up to `fraction` of the spacing (deterministic pseudo-random).
inline void perturb_interior(Mesh& m, double dx, double dy, double fraction, unsigned seed = 1) {
  std::vector<char> boundary(m.num_points(), 0);
  for (const auto& tag : m.tags)
    for (Index p : tag.points) boundary[p] = 1;
  unsigned state = seed;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / double(1u << 24) * 2 - 1;
  };
  for (Index p = 0; p < m.num_points(); ++p) {
    const double rx = next(), ry = next();
    if (boundary[p]) continue;
    m.x[p] += fraction * dx * rx;
    m.y[p] += fraction * dy * ry;
  }
}

}  // namespace stagger::testing
