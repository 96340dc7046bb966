// Second order in space and time on a smooth flow with mesh motion: the Taylor-Green
// vortex with its energy source (docs/verification.md §5), and Noh on the polar mesh
// (radial symmetry to round-off with the edge viscosity).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "problems.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
using namespace testing;

namespace {
double taylor_green_l2_velocity(int n, double t_end) {
  Problem p = gas_problem(rectangle_mesh(1.0, 1.0, n, n), 5.0 / 3.0, t_end);
  RegionSetup r = gas_region(constant_field(1.0));
  r.pressure = [](double x, double y) { return taylor_green_pressure(x, y); };
  r.velocity_x = [](double x, double y) { return taylor_green_velocity(x, y)[0]; };
  r.velocity_y = [](double x, double y) { return taylor_green_velocity(x, y)[1]; };
  p.regions.push_back(r);
  walls(p);
  p.sources = taylor_green_sources();
  p.options.hourglass_coefficient = 0;
  p.options.q1 = p.options.q2 = 0;
  Simulation sim(std::move(p));
  sim.advance_to(t_end);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  NamedValues errors, diagnostics;
  taylor_green_reference()(sim, errors, diagnostics);
  for (const auto& [name, value] : errors)
    if (name == "L2_velocity") return value;
  ADD_FAILURE() << "taylor_green_reference gave no L2_velocity";
  return 0;
}
}  // namespace

TEST(SmoothFlow, TaylorGreenConvergesAtSecondOrder) {
  const double e16 = taylor_green_l2_velocity(16, 0.5), e32 = taylor_green_l2_velocity(32, 0.5),
               e64 = taylor_green_l2_velocity(64, 0.5);
  const double order1 = std::log2(e16 / e32), order2 = std::log2(e32 / e64);
  std::printf("taylor-green L2_velocity: %.4e %.4e %.4e orders %.3f %.3f\n", e16, e32, e64, order1, order2);
  EXPECT_GE(order2, 1.9);
}

TEST(Noh, PolarMeshStaysRadiallySymmetricWithTheEdgeViscosity) {
  Problem p = gas_problem(build_mesh(meshgen::annulus_sector(0.0, 1.0, 0.0, M_PI / 2, 10, 50)), 5.0 / 3.0, 0.6);
  RegionSetup r = gas_region(constant_field(1.0));
  r.specific_internal_energy = constant_field(0.0);
  r.velocity_x = [](double x, double y) {
    const double d = std::hypot(x, y);
    return d > 0 ? -x / d : 0.0;
  };
  r.velocity_y = [](double x, double y) {
    const double d = std::hypot(x, y);
    return d > 0 ? -y / d : 0.0;
  };
  p.regions.push_back(r);
  walls(p, {"start", "end"});
  p.boundaries.push_back(boundary("outer", BoundaryKind::free));
  p.options.viscosity = Viscosity::edge;
  p.options.hourglass_coefficient = 0;
  Simulation sim(std::move(p));
  sim.advance_to(0.6);
  NamedValues errors, diagnostics;
  noh_reference()(sim, errors, diagnostics);
  double asym = -1, plateau = -1, shock = 0;
  for (const auto& [name, value] : diagnostics) {
    if (name == "asymmetry") asym = value;
    if (name == "plateau_density") plateau = value;
  }
  // Shock: the outermost zone centre still above the half-way density 10.
  const Mesh& m = sim.mesh();
  for (Index z = 0; z < m.num_zones(); ++z) {
    double cx = 0, cy = 0;
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) cx += sim.x()[m.corner_point[b + k]] / n, cy += sim.y()[m.corner_point[b + k]] / n;
    if (sim.density()[z] > 10) shock = std::max(shock, std::hypot(cx, cy));
  }
  std::printf("noh polar 10x50: cycles %ld plateau %.3f shock %.4f asymmetry %.2e audit %.2e\n", sim.cycle(), plateau,
              shock, asym, sim.energy().relative_error);
  EXPECT_LT(asym, 1e-10);
  EXPECT_GT(plateau, 14.5);
  EXPECT_NEAR(shock, 0.2, 0.01);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger
