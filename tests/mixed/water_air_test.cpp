// The water-air shock tube (apps/scenes/water_air.toml, interface on a zone boundary) against
// the exact two-stiffened-gas solution (lib/src/verify/stiffened_riemann.cpp): L1(rho)
// converges under refinement and the pressure of the air (right of the contact) stays below 1.01 p*.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

struct TubeErrors {
  double l1_density = 0, max_pressure_right = 0, energy_error = 0;
};

TubeErrors run_tube(int refine, const StiffenedRiemann& exact) {
  Scene scene = load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/water_air.toml",
                           {{"mesh.refine", std::to_string(refine)}, {"output.dump_interval", "1"}});
  const double t_end = scene.problem.t_end;
  Simulation simulation(std::move(scene.problem));
  simulation.advance_to(t_end);
  const auto centres = zone_centres(simulation.mesh(), simulation.x(), simulation.y());
  const auto areas = zone_areas(simulation.mesh(), simulation.x(), simulation.y());
  const Index air = simulation.mesh().region_index("air");
  TubeErrors errors;
  double total_area = 0;
  for (std::size_t z = 0; z < areas.size(); ++z) {
    const double x = centres[0][z];
    errors.l1_density += areas[z] * std::abs(simulation.density()[z] - exact.sample(x, simulation.time()).density);
    total_area += areas[z];
    if (simulation.mesh().zone_region[z] == air)
      errors.max_pressure_right = std::max(errors.max_pressure_right, simulation.pressure()[z]);
  }
  errors.l1_density /= total_area;
  errors.energy_error = simulation.energy().relative_error;
  return errors;
}

}  // namespace

TEST(WaterAir, DensityConvergesWithoutAPressureOvershootAtTheContact) {
  const StiffenedRiemann exact({{1000.0, 0.0, 1e9}, 4.4, 6e8}, {{10.0, 0.0, 1e5}, 1.4, 0.0}, 0.7);
  std::vector<TubeErrors> ladder;
  for (int refine : {1, 2, 4}) ladder.push_back(run_tube(refine, exact));
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    std::printf("refine %d: L1(rho) = %.6g, max p of the air / p* = %.6f, audit %.3g\n", 1 << k, ladder[k].l1_density,
                ladder[k].max_pressure_right / exact.star_pressure(), ladder[k].energy_error);
    EXPECT_LT(ladder[k].max_pressure_right, 1.01 * exact.star_pressure());
    EXPECT_LT(std::abs(ladder[k].energy_error), 1e-12);
  }
  EXPECT_LT(ladder[1].l1_density, 0.8 * ladder[0].l1_density);
  EXPECT_LT(ladder[2].l1_density, 0.8 * ladder[1].l1_density);
}

}  // namespace stagger
