// Subzonal pressures in a run (docs/algorithm.md §18): on a mixed quad/triangle mesh the energy
// audit stays at round-off and a restart continues bitwise. The kernel itself is checked in
// tests/kernels/subzonal_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {

// A blast in a walled box of mixed quads and triangles, perturbed.
Problem blast_problem(Hourglass h, double coefficient) {
  const PolygonSoup quads = meshgen::rectangle(0, 1, 0, 1, 12, 12);
  PolygonSoup soup = quads;  // every third quad split into two triangles
  soup.polygon_begin = {0};
  soup.polygon_points.clear();
  soup.polygon_region.clear();
  for (std::size_t i = 0; i < quads.num_polygons(); ++i) {
    const auto* q = quads.polygon_points.data() + quads.polygon_begin[i];
    if (i % 3 == 1) {
      soup.add_polygon({q[0], q[1], q[2]}, quads.polygon_region[i]);
      soup.add_polygon({q[0], q[2], q[3]}, quads.polygon_region[i]);
    } else {
      soup.add_polygon({q[0], q[1], q[2], q[3]}, quads.polygon_region[i]);
    }
  }
  for (std::size_t q = 0; q < soup.x.size(); ++q) {
    const double x = soup.x[q], y = soup.y[q];
    if (x > 0 && x < 1 && y > 0 && y < 1) {
      soup.x[q] += 0.02 * std::sin(17.0 * q);
      soup.y[q] += 0.02 * std::cos(11.0 * q);
    }
  }
  Problem p = testing::gas_problem(build_mesh(soup), 1.4, 0.1, "subzonal");
  EXPECT_FALSE(p.mesh.all_quads());
  RegionSetup r = testing::gas_region(constant_field(1.0));
  r.specific_internal_energy = [](double x, double y) { return std::hypot(x - 0.3, y - 0.4) < 0.2 ? 1.0 : 0.01; };
  p.regions.push_back(r);
  testing::walls(p);
  p.options.hourglass = h;
  p.options.hourglass_coefficient = coefficient;
  return p;
}

}  // namespace

TEST(Subzonal, EnergyAuditAndMomentumStayAtRoundOffInARun) {
  // Subzonal pressures on every zone: the audit closes to round-off and the option acts.
  auto run = [](Hourglass h, double coefficient) {
    Simulation sim(blast_problem(h, coefficient));
    sim.advance_to(0.1);
    EXPECT_GT(sim.cycle(), 20);
    EXPECT_LT(std::abs(sim.energy().relative_error), 1e-13);
    return std::vector<double>(sim.x().begin(), sim.x().end());
  };
  const std::vector<double> off = run(Hourglass::subzonal, 0.0);
  for (Hourglass h : {Hourglass::subzonal, Hourglass::subzonal_triangles}) {
    const std::vector<double> on = run(h, 1.0);
    double change = 0;
    for (std::size_t i = 0; i < on.size(); ++i) change = std::max(change, std::abs(on[i] - off[i]));
    EXPECT_GT(change, 1e-6);  // the subzonal forces moved the points
  }
}

TEST(Subzonal, ARestartContinuesBitwise) {
  // The subzone masses are not in the checkpoint: rebuilt from the initial mesh, they are
  // the same, so a restored run repeats the original bit for bit.
  for (Hourglass h : {Hourglass::subzonal, Hourglass::subzonal_triangles}) {
    Simulation first(blast_problem(h, 2.0));
    for (int i = 0; i < 10; ++i) first.step();
    const std::string blob = first.checkpoint();
    for (int i = 0; i < 10; ++i) first.step();
    Simulation second(blast_problem(h, 2.0));
    second.restore(blob);
    for (int i = 0; i < 10; ++i) second.step();
    ASSERT_EQ(first.cycle(), 20);
    ASSERT_EQ(second.cycle(), 20);
    for (std::size_t q = 0; q < first.x().size(); ++q) {
      ASSERT_EQ(first.x()[q], second.x()[q]) << q;
      ASSERT_EQ(first.y()[q], second.y()[q]) << q;
    }
    for (std::size_t z = 0; z < first.specific_internal_energy().size(); ++z)
      ASSERT_EQ(first.specific_internal_energy()[z], second.specific_internal_energy()[z]) << z;
  }
}

}  // namespace stagger
