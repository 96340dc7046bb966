// Exact conservation: total energy (with boundary work) and momentum to round-off, and
// exact preservation of uniform states (docs/algorithm.md §1, §10, §11).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "problems.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
using namespace testing;

TEST(Conservation, EnergyAuditClosesWithAPistonOnAPerturbedMesh) {
  Mesh mesh = rectangle_mesh(1.0, 0.5, 20, 10);
  perturb_interior(mesh, 0.05, 0.05, 0.2);
  Problem p = gas_problem(std::move(mesh), 5.0 / 3.0, 0.3);
  p.regions.push_back(uniform_region(1.0, 1.0));
  BoundaryCondition piston = boundary("left", BoundaryKind::velocity);
  piston.velocity_x = [](double t) { return 0.5 + 0.25 * std::sin(10 * t); };
  p.boundaries.push_back(piston);
  walls(p, {"right", "bottom", "top"});
  Simulation sim(std::move(p));
  sim.advance_to(0.3);
  const EnergyAudit a = sim.energy();
  EXPECT_GT(a.boundary_work, 0.1);  // the piston did real work
  EXPECT_LT(std::abs(a.relative_error), 1e-12);
}

TEST(Conservation, EnergyAuditClosesWithAppliedPressureAndEdgeViscosity) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
  perturb_interior(mesh, 1.0 / 12, 1.0 / 12, 0.25, 7);
  Problem p = gas_problem(std::move(mesh), 1.4, 0.2);
  p.regions.push_back(uniform_region(1.0, 1.0));
  BoundaryCondition push = boundary("right", BoundaryKind::pressure);
  push.pressure = [](double t) { return 1.5 + 5 * t; };
  p.boundaries.push_back(push);
  walls(p, {"left", "bottom"});
  p.boundaries.push_back(boundary("top", BoundaryKind::free));
  p.options.viscosity = Viscosity::edge;
  p.options.hourglass = Hourglass::flanagan_belytschko;
  p.options.hourglass_coefficient = 1.0;
  Simulation sim(std::move(p));
  sim.advance_to(0.2);
  EXPECT_GT(std::abs(sim.energy().boundary_work), 1e-2);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

TEST(Conservation, MomentumIsConservedInAPeriodicBoxWithRandomVelocities) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 16, 16);
  Problem p = gas_problem(std::move(mesh), 1.4, 0.1);
  RegionSetup r = uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double y) { return 0.3 * std::sin(2 * M_PI * x) * std::cos(4 * M_PI * y) + 0.2; };
  r.velocity_y = [](double x, double y) { return 0.2 * std::cos(6 * M_PI * x + 1) * std::sin(2 * M_PI * y) - 0.1; };
  p.regions.push_back(r);
  BoundaryCondition left = boundary("left", BoundaryKind::periodic),
                    bottom = boundary("bottom", BoundaryKind::periodic);
  left.partner = "right";
  bottom.partner = "top";
  p.boundaries = {left, bottom};
  p.options.hourglass_coefficient = 0.1;
  Simulation sim(std::move(p));
  const auto m0 = sim.momentum();
  double scale = 0;
  for (std::size_t i = 0; i < sim.point_mass().size(); ++i)
    scale += sim.point_mass()[i] * (std::abs(sim.velocity_x()[i]) + std::abs(sim.velocity_y()[i]));
  sim.advance_to(0.1);
  const auto m1 = sim.momentum();
  EXPECT_GT(sim.cycle(), 20);
  EXPECT_LT(std::abs(m1[0] - m0[0]) / scale, 1e-14);
  EXPECT_LT(std::abs(m1[1] - m0[1]) / scale, 1e-14);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-13);
}

TEST(Conservation, UniformFlowIsPreservedOnAPerturbedPeriodicMesh) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 10, 10);
  Problem p = gas_problem(std::move(mesh), 1.4, 0.2);
  p.regions.push_back(uniform_region(1.0, 1.0, 1.0, 0.5));
  BoundaryCondition left = boundary("left", BoundaryKind::periodic),
                    bottom = boundary("bottom", BoundaryKind::periodic);
  left.partner = "right";
  bottom.partner = "top";
  p.boundaries = {left, bottom};
  Simulation sim(std::move(p));
  sim.advance_to(0.2);
  for (std::size_t i = 0; i < sim.velocity_x().size(); ++i) {
    EXPECT_NEAR(sim.velocity_x()[i], 1.0, 1e-13);
    EXPECT_NEAR(sim.velocity_y()[i], 0.5, 1e-13);
  }
  for (double rho : sim.density()) EXPECT_NEAR(rho, 1.0, 1e-12);
  for (double pr : sim.pressure()) EXPECT_NEAR(pr, 1.0, 1e-12);
}

TEST(Conservation, ConstantStateAtRestStaysConstantInAWalledBox) {
  Mesh mesh = rectangle_mesh(2.0, 1.0, 8, 4);
  perturb_interior(mesh, 0.25, 0.25, 0.3, 3);
  Problem p = gas_problem(std::move(mesh), 1.4, 0.5);
  p.regions.push_back(uniform_region(2.0, 3.0));
  walls(p);
  Simulation sim(std::move(p));
  sim.advance_to(0.5);
  for (double v : sim.velocity_x()) EXPECT_NEAR(v, 0.0, 1e-13);
  for (double v : sim.velocity_y()) EXPECT_NEAR(v, 0.0, 1e-13);
  for (double pr : sim.pressure()) EXPECT_NEAR(pr, 3.0, 1e-12);
}

// A fixed (clamped) boundary: both velocity components zero, so a shear flow along it does
// not slide its points (a wall would). Its points never move, its work is exactly zero and
// the audit closes; on an rz mesh too, the fixed side off the axis, and with the ALE remapping
// after every cycle.
TEST(Conservation, AFixedBoundaryHoldsItsPointsAndDoesNoWork) {
  for (const auto& [geometry, ale] :
       {std::pair{CoordinateSystem::planar, false}, std::pair{CoordinateSystem::rz, false},
        std::pair{CoordinateSystem::planar, true}}) {
    Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
    perturb_interior(mesh, 1.0 / 12, 1.0 / 12, 0.2, 5);
    Problem p = gas_problem(std::move(mesh), 1.4, 0.1);
    RegionSetup r = gas_region(constant_field(1.0));
    r.pressure = [](double x, double y) {
      return 1 + 4 * std::exp(-20 * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)));
    };
    r.velocity_x = [](double, double y) { return 0.2 * y; };
    r.velocity_y = constant_field(0.5);  // along the clamped side: a wall there would let it slide
    p.regions.push_back(r);
    const char* clamped = geometry == CoordinateSystem::rz ? "right" : "left";
    p.boundaries.push_back(boundary(clamped, BoundaryKind::fixed));
    for (const char* tag : {"left", "right", "bottom", "top"})
      if (std::string(tag) != clamped) p.boundaries.push_back(boundary(tag, BoundaryKind::free));
    p.options.geometry = geometry;
    if (ale) p.ale.mode = AleMode::ale, p.ale.remap_every = 1;  // the rezone keeps the clamped points
    Simulation sim(std::move(p));
    const BoundaryTag& tag = sim.mesh().tags[sim.mesh().tag_index(clamped)];
    sim.advance_to(0.1);
    EXPECT_GT(sim.cycle(), 20);
    for (Index q : tag.points) {
      EXPECT_EQ(sim.x()[q], sim.problem().mesh.x[q]) << "point " << q;
      EXPECT_EQ(sim.y()[q], sim.problem().mesh.y[q]) << "point " << q;
      EXPECT_EQ(sim.velocity_x()[q], 0.0) << "point " << q;
      EXPECT_EQ(sim.velocity_y()[q], 0.0) << "point " << q;
    }
    EXPECT_EQ(sim.energy().boundary_work, 0.0);
    EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  }
}

}  // namespace stagger
