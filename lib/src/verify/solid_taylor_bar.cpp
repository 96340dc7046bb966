/// @file solid_taylor_bar.cpp
/// Shape diagnostics of a Taylor bar on a rigid wall (docs/solids.md §8): no exact solution,
/// the numbers the experiments and codes compare.
#include <algorithm>
#include <limits>

#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {

Reference taylor_bar_reference() {
  return [](const Simulation& simulation, NamedValues&, NamedValues& diagnostics) {
    // The wall is the line y = y0 the bar stands on: the lowest y of the initial mesh.
    const Mesh& mesh = simulation.mesh();
    const double inf = std::numeric_limits<double>::infinity();
    double y0 = inf, top0 = -inf;
    for (const double y : mesh.y) y0 = std::min(y0, y), top0 = std::max(top0, y);
    const double length0 = top0 - y0;
    const auto x = simulation.x(), y = simulation.y();
    double top = -inf, lo = inf, hi = -inf, face_lo = inf, face_hi = -inf;
    for (std::size_t p = 0; p < x.size(); ++p) {
      top = std::max(top, y[p]);
      lo = std::min(lo, x[p]), hi = std::max(hi, x[p]);
      // On the wall: its points keep y = y0 to round-off (docs/algorithm.md §10).
      if (y[p] <= y0 + 1e-9 * length0) face_lo = std::min(face_lo, x[p]), face_hi = std::max(face_hi, x[p]);
    }
    double eps_max = 0;
    for (const double eps : simulation.plastic_strain()) eps_max = std::max(eps_max, eps);
    diagnostics.emplace_back("final_length", top - y0);
    diagnostics.emplace_back("length_ratio", (top - y0) / length0);
    diagnostics.emplace_back("impact_face_width", face_hi >= face_lo ? face_hi - face_lo : 0.0);
    diagnostics.emplace_back("max_width", hi - lo);
    diagnostics.emplace_back("max_plastic_strain", eps_max);
  };
}

}  // namespace stagger
