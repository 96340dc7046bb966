// The step applies the subzonal pressures with the scene's merit factor (docs/algorithm.md §18),
// by an exact property rather than a golden number: in one step from rest with one point set
// moving, the part of that point's velocity change that the subzonal pressures make (the run
// with `hourglass_coefficient` = alpha less the run with 0) is dt / m_p times the kernel's
// forces at the half-step geometry, dp_k = alpha c^2 (m_k / V_k - rho_z), with the gas's c^2.
// No viscosity; the pressure forces, the same in both runs, cancel; what is left differs by the
// square of the point's move (a 1e-6 move: 1e-6 relative).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/subzonal_pressure.hpp"
#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {
namespace {

constexpr double kDt = 1e-3, kMove = 1e-3;  // the point moves kMove * kDt = 1e-6 in the step

// A 2 x 2 box of gas at rest, the middle point (0.5, 0.5) given v = (1e-3, 0): the velocity
// change of that point in one step of dt = 1e-3 with the merit factor alpha.
double middle_point_velocity_change(double alpha, Hourglass shape, bool rz) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(1.0, 1.0, 2, 2), 1.4, 1.0);
  RegionSetup r = testing::uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double y) { return x == 0.5 && y == 0.5 ? kMove : 0.0; };
  p.regions.push_back(r);
  testing::walls(p);
  p.options.viscosity = Viscosity::bulk;
  p.options.q1 = p.options.q2 = 0;
  p.options.hourglass = shape;
  p.options.hourglass_coefficient = alpha;
  p.options.dt_init = p.options.dt_max = kDt;
  if (rz) p.options.geometry = CoordinateSystem::rz;
  Simulation sim(std::move(p));
  sim.step();
  EXPECT_EQ(sim.dt(), kDt);
  return sim.velocity_x()[4] - kMove;  // point 4: the middle of a 3 x 3 point grid
}

// dt / m_p times the x force of the subzonal pressures on the middle point, from the kernel:
// the four zones at the half-step geometry (the middle point moved by dt / 2 v), the subzone
// masses of the initial mesh, c^2 = gamma p / rho = 1.4.
double kernel_velocity_change(double alpha, Subzones subzones) {
  double force = 0, point_mass = 0;
  const double half = 0.5 * kDt * kMove;
  for (int zx = 0; zx < 2; ++zx)
    for (int zy = 0; zy < 2; ++zy) {
      ZoneVertices v0;
      v0.n = 4;
      const double x0 = 0.5 * zx, y0 = 0.5 * zy;
      const double xs[4] = {x0, x0 + 0.5, x0 + 0.5, x0}, ys[4] = {y0, y0, y0 + 0.5, y0 + 0.5};
      int middle = -1;
      for (int k = 0; k < 4; ++k) {
        v0.x[k] = xs[k], v0.y[k] = ys[k];
        if (xs[k] == 0.5 && ys[k] == 0.5) middle = k;
      }
      double mass[kMaxZoneVertices], fx[kMaxZoneVertices] = {}, fy[kMaxZoneVertices] = {};
      subzonal_masses(v0, 1.0, subzones, mass);
      double zone_mass = 0;
      for (int k = 0; k < 4; ++k) zone_mass += mass[k];
      ZoneVertices v = v0;
      v.x[middle] += half;
      add_subzonal_pressure_forces(v, mass, zone_mass, PlanarGeometry::area(v), 1.4, alpha, subzones, fx, fy);
      force += fx[middle];
      point_mass += 0.25 * zone_mass;  // the middle point's share of each zone (a square's median corner)
    }
  return kDt * force / point_mass;
}

void expect_the_kernels_subzonal_forces(bool rz) {
  const std::pair<Hourglass, Subzones> shapes[] = {{Hourglass::subzonal, Subzones::corners},
                                                   {Hourglass::subzonal_triangles, Subzones::triangles}};
  for (const auto& [shape, subzones] : shapes)
    for (const double alpha : {0.7, 2.0}) {
      const double step = middle_point_velocity_change(alpha, shape, rz) - middle_point_velocity_change(0.0, shape, rz);
      const double kernel = kernel_velocity_change(alpha, subzones);
      std::printf("rz %d, alpha %.1f, %s: subzonal velocity change %.9e, kernel %.9e (ratio %.7f)\n", rz, alpha,
                  subzones == Subzones::corners ? "corners" : "triangles", step, kernel, step / kernel);
      ASSERT_LT(kernel, 0.0);  // restoring
      EXPECT_NEAR(step / kernel, 1.0, 1e-4) << "alpha " << alpha;
    }
}

}  // namespace

TEST(SubzonalCoefficient, TheStepAppliesTheMeritFactorAsTheKernelDefinesIt) {
  expect_the_kernels_subzonal_forces(false);
}

// rz: the area-weighted forces of the planar subzone masses over the planar point mass, the
// same acceleration (docs/algorithm.md §19).
TEST(SubzonalCoefficient, TheStepAppliesTheMeritFactorAsTheKernelDefinesItInRz) {
  expect_the_kernels_subzonal_forces(true);
}

}  // namespace stagger
