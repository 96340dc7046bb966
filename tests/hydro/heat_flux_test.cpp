// The artificial heat flux in the step (docs/algorithm.md §21): the total energy audit stays at
// round-off in planar and rz while the heat flux moves internal energy, and its stability
// limit shows in dt_limit when it is the smallest. The kernel is tested in
// tests/kernels/heat_flux_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "problems.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
using namespace testing;

namespace {

// A converging flow with a hot spot on a perturbed quarter [0, 1]^2: walls on x = 0 (the axis
// in rz) and y = 0, the rest free.
Problem hot_implosion(bool rz, double c1, double c2) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
  perturb_interior(mesh, 1.0 / 12, 1.0 / 12, 0.25, 5);
  Problem p = gas_problem(std::move(mesh), 5.0 / 3.0, 0.1);
  RegionSetup r = uniform_region(1.0, 0.1);
  r.pressure = [](double x, double y) { return 0.1 + 2.0 * std::exp(-20 * ((x - 0.3) * (x - 0.3) + y * y)); };
  r.velocity_x = [](double x, double) { return -0.5 * x; };
  r.velocity_y = [](double, double y) { return -0.5 * y; };
  p.regions.push_back(r);
  walls(p, {"left", "bottom"});
  p.options.viscosity = Viscosity::edge;
  p.options.hourglass = Hourglass::gamma;
  p.options.hourglass_coefficient = 0.1;
  if (rz) p.options.geometry = CoordinateSystem::rz;
  p.options.heat_flux_c1 = c1;
  p.options.heat_flux_c2 = c2;
  return p;
}

}  // namespace

TEST(HeatFlux, TotalEnergyIsExactInBothGeometriesAndTheHeatFluxActs) {
  for (bool rz : {false, true}) {
    Simulation off(hot_implosion(rz, 0, 0)), on(hot_implosion(rz, 2.0, 1.0));
    double worst = 0;
    on.set_observer([&](const Simulation& s) { worst = std::max(worst, std::abs(s.energy().relative_error)); });
    off.advance_to(0.1);
    on.advance_to(0.1);
    EXPECT_GT(on.cycle(), 20);
    EXPECT_LT(worst, 1e-12) << (rz ? "rz" : "planar");
    // It moved energy: the hot spot is cooler and the field differs from the run without it.
    double largest_change = 0;
    for (std::size_t z = 0; z < on.specific_internal_energy().size(); ++z)
      largest_change =
          std::max(largest_change, std::abs(on.specific_internal_energy()[z] - off.specific_internal_energy()[z]));
    EXPECT_GT(largest_change, 1e-2) << (rz ? "rz" : "planar");
    const auto hottest = [](const Simulation& s) {
      return *std::max_element(s.specific_internal_energy().begin(), s.specific_internal_energy().end());
    };
    EXPECT_LT(hottest(on), hottest(off)) << (rz ? "rz" : "planar");
  }
}

TEST(HeatFlux, ItsStabilityLimitIsReportedWhenItIsTheSmallest) {
  Simulation sim(hot_implosion(true, 40.0, 0.0));
  int heat_limited = 0;
  sim.set_observer([&](const Simulation& s) {
    if (s.dt_limit().rfind("heat-flux limit of zone ", 0) == 0) ++heat_limited;
  });
  sim.advance_to(0.02);
  EXPECT_GT(heat_limited, sim.cycle() / 2);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

// The heat flux's stability limit (docs/algorithm.md §21) is what keeps an explicit conduction
// bounded: a hot spot in gas at rest in pressure, conduction far faster than sound (c1 = 40), stays within
// its initial range of e (a maximum principle) in planar and rz, and the limit bound most steps.
TEST(HeatFlux, ItsTimeStepLimitKeepsConductionWithinTheInitialRange) {
  for (bool rz : {false, true}) {
    Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
    Problem p = gas_problem(std::move(mesh), 5.0 / 3.0, 0.02);
    RegionSetup r = uniform_region(1.0, 0.1);
    // In pressure equilibrium: a light, hot spot (e 3.3 times the surroundings').
    r.density = [](double x, double y) { return 1.0 - 0.7 * std::exp(-20 * ((x - 0.3) * (x - 0.3) + y * y)); };
    p.regions.push_back(r);
    walls(p);
    if (rz) p.options.geometry = CoordinateSystem::rz;
    p.options.heat_flux_c1 = 40.0;
    Simulation sim(std::move(p));
    const auto e0 = sim.specific_internal_energy();
    const double lo = *std::min_element(e0.begin(), e0.end()), hi = *std::max_element(e0.begin(), e0.end());
    double coldest = lo, hottest = hi;
    int heat_limited = 0;
    sim.set_observer([&](const Simulation& s) {
      for (double e : s.specific_internal_energy()) coldest = std::min(coldest, e), hottest = std::max(hottest, e);
      if (s.dt_limit().rfind("heat-flux limit of zone ", 0) == 0) ++heat_limited;
    });
    sim.advance_to(0.02);
    std::printf("rz %d: e in [%.6f, %.6f] against the initial [%.6f, %.6f]; %d of %ld steps heat-limited\n", rz,
                coldest, hottest, lo, hi, heat_limited, sim.cycle());
    EXPECT_GT(heat_limited, sim.cycle() / 2) << (rz ? "rz" : "planar");
    // The gas moves a little (conduction changes the pressure): a margin of 2% of the range.
    EXPECT_GE(coldest, lo - 0.02 * (hi - lo)) << (rz ? "rz" : "planar");
    EXPECT_LE(hottest, hi + 0.02 * (hi - lo)) << (rz ? "rz" : "planar");
  }
}

}  // namespace stagger
