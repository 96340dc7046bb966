// Christensen's limiter of the edge viscosity (docs/algorithm.md §5), by an exact property: a
// linear velocity field has the same velocity gradient along every grid line, every ratio is 1,
// and the limited viscosity vanishes; a uniform compression then runs as without viscosity.
// Walls on two sides and pistons moving with the flow on the others (mirror continuations,
// ratio 1 for the edges normal to them), in planar and rz.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {
namespace {

// Gas at uniform pressure compressed uniformly, v = -0.5 (x, y) (each point coasts: no
// pressure gradient), on a mesh graded in x; 30 cycles.
std::vector<double> compressed_positions(bool rz, double edge_c1, double edge_c2, bool limiter) {
  Mesh mesh = testing::rectangle_mesh(1.0, 1.0, 12, 10);
  for (double& x : mesh.x) x = x * (0.5 + 0.5 * x);
  Problem p = testing::gas_problem(std::move(mesh), 1.4, 1.0);
  RegionSetup r = testing::uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double) { return -0.5 * x; };
  r.velocity_y = [](double, double y) { return -0.5 * y; };
  p.regions.push_back(r);
  testing::walls(p, {"left", "bottom"});
  BoundaryCondition right = testing::boundary("right", BoundaryKind::velocity),
                    top = testing::boundary("top", BoundaryKind::velocity);
  right.velocity_x = constant_in_time(-0.5);  // the normal component (a piston)
  top.velocity_y = constant_in_time(-0.5);
  p.boundaries.push_back(right);
  p.boundaries.push_back(top);
  if (rz) p.options.geometry = CoordinateSystem::rz;
  p.options.viscosity = Viscosity::edge;
  p.options.edge_c1 = edge_c1;
  p.options.edge_c2 = edge_c2;
  p.options.edge_limiter = limiter;
  Simulation sim(std::move(p));
  while (sim.cycle() < 30) sim.step();
  std::vector<double> xy(sim.x().begin(), sim.x().end());
  xy.insert(xy.end(), sim.y().begin(), sim.y().end());
  return xy;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

void expect_a_linear_compression_to_feel_no_limited_viscosity(bool rz) {
  const auto inviscid = compressed_positions(rz, 0, 0, true);
  const auto limited = compressed_positions(rz, 0.5, 1.0, true);
  const auto unlimited = compressed_positions(rz, 0.5, 1.0, false);
  const double d_limited = largest_difference(limited, inviscid), d_unlimited = largest_difference(unlimited, inviscid);
  std::printf("rz %d: largest position difference from the inviscid run: limited %.3e, unlimited %.3e\n", rz, d_limited,
              d_unlimited);
  EXPECT_LT(d_limited, 1e-13);
  EXPECT_GT(d_unlimited, 1e-5) << "without the limiter the viscosity must act for the test to mean anything";
}

}  // namespace

TEST(EdgeViscosityLimiter, ALinearCompressionFeelsNoViscosity) {
  expect_a_linear_compression_to_feel_no_limited_viscosity(false);
}

TEST(EdgeViscosityLimiter, ALinearCompressionFeelsNoViscosityInRz) {
  expect_a_linear_compression_to_feel_no_limited_viscosity(true);
}

}  // namespace stagger
