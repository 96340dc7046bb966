#pragma once
// The L1 density error of a run of Sod's tube against the exact solution (docs/verification.md §1).
#include <cmath>

#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger::testing {

/// Area-weighted mean |rho - rho_exact| at the zone centres (vertex averages) at the run's time.
inline double sod_l1_density(const Simulation& sim) {
  const ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
  const Mesh& m = sim.mesh();
  double num = 0, den = 0;
  for (Index z = 0; z < m.num_zones(); ++z) {
    double cx = 0;
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) cx += sim.x()[m.corner_point[b + k]] / n;
    num += sim.zone_area()[z] * std::abs(sim.density()[z] - exact.sample(cx, sim.time()).density);
    den += sim.zone_area()[z];
  }
  return num / den;
}

}  // namespace stagger::testing
