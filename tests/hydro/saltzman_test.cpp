// Saltzman piston on the skewed mesh (docs/verification.md §4): runs to t = 0.6 with the
// paper's bulk q; shock at 4t/3, density 4 behind it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "problems.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
using namespace testing;

Problem saltzman_problem(Hourglass kind, double q_hg) {
  Mesh mesh = rectangle_mesh(1.0, 0.1, 100, 10);
  for (Index p = 0; p < mesh.num_points(); ++p) mesh.x[p] += (0.1 - mesh.y[p]) * std::sin(M_PI * mesh.x[p]);
  Problem p = gas_problem(std::move(mesh), 5.0 / 3.0, 0.6);
  RegionSetup r = gas_region(constant_field(1.0));
  r.specific_internal_energy = constant_field(1e-10);
  p.regions.push_back(r);
  BoundaryCondition piston = boundary("left", BoundaryKind::velocity);
  piston.velocity_x = constant_in_time(1.0);
  p.boundaries.push_back(piston);
  walls(p, {"right", "bottom", "top"});
  p.options.hourglass = kind;
  p.options.hourglass_coefficient = q_hg;
  return p;
}

TEST(Saltzman, RunsToTheEndWithTheShockInPlaceAndEnergyConserved) {
  Simulation sim(saltzman_problem(Hourglass::flanagan_belytschko, 1.0));
  sim.advance_to(0.6);
  // Mean density of zones between 0.2 and 0.7 (behind the shock at 0.8).
  double sum = 0;
  int count = 0;
  const Mesh& m = sim.mesh();
  double front = 0;
  for (Index z = 0; z < m.num_zones(); ++z) {
    double cx = 0;
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) cx += sim.x()[m.corner_point[c]] / 4;
    if (cx > 0.65 && cx < 0.75) sum += sim.density()[z], ++count;
    if (sim.density()[z] > 2.5) front = std::max(front, cx);
  }
  std::printf("saltzman: cycles %ld plateau %.4f front %.4f audit %.2e\n", sim.cycle(), sum / count, front,
              sim.energy().relative_error);
  EXPECT_NEAR(sum / count, 4.0, 0.15);
  EXPECT_NEAR(front, 0.8, 0.02);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger
