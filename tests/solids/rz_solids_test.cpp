// Strength in rz (docs/algorithm.md §19) on the shipped scenes, coarse and short: the Taylor
// anvil with linear hardening (audit at round-off, the axis and the wall held, every zone on or
// inside its hardened 3D yield surface) and Verney's spherical shell (the be_shell reference in
// rz: the spherical exact solution of docs/derivations.md section 2.1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "support/named_values.hpp"

namespace stagger {
namespace {

using testing::value_of;

Scene scene(const std::string& name, const std::vector<std::pair<std::string, std::string>>& overrides) {
  return load_scene(std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/" + name + ".toml", overrides);
}

}  // namespace

TEST(RzStrength, TaylorAnvilWithHardeningKeepsTheAuditTheAxisAndTheYieldSurface) {
  // 5 x 50 zones, 12 us: the plastic front has run well into the rod.
  Scene s = scene("taylor_anvil", {{"mesh.refine", "0.5"}, {"time.end", "12e-6"}});
  ASSERT_EQ(s.problem.options.geometry, CoordinateSystem::rz);
  ASSERT_TRUE(s.problem.materials[0].strength);
  const Strength strength = std::get<Strength>(*s.problem.materials[0].strength);
  ASSERT_GT(strength.hardening_modulus, 0.0);
  const Reference reference = s.control.reference;
  Simulation sim(std::move(s.problem));
  int axis_points = 0;
  sim.set_observer([&](const Simulation& state) {
    axis_points = 0;
    for (std::size_t p = 0; p < state.x().size(); ++p) {
      ASSERT_GE(state.x()[p], 0.0) << "point " << p;
      if (state.x()[p] == 0) {
        ASSERT_EQ(state.velocity_x()[p], 0.0) << "axis point " << p;
        ++axis_points;
      }
    }
  });
  sim.advance_to(12e-6);
  EXPECT_EQ(axis_points, 51);
  EXPECT_GT(sim.cycle(), 500);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);

  // Every zone on or inside Y0 + H eps_p, with the hoop deviator S_thth = -(S_rr + S_zz); the
  // foot has hardened.
  const auto sxx = sim.stress_xx(), syy = sim.stress_yy(), sxy = sim.stress_xy(), eps = sim.plastic_strain();
  double largest_eps = 0;
  int on_surface = 0;
  for (std::size_t z = 0; z < eps.size(); ++z) {
    const double stt = -(sxx[z] + syy[z]);
    const double sigma = std::sqrt(1.5 * (sxx[z] * sxx[z] + syy[z] * syy[z] + stt * stt + 2 * sxy[z] * sxy[z]));
    const double yield = strength.yield_stress + strength.hardening_modulus * eps[z];
    EXPECT_LE(sigma, yield * (1 + 1e-12)) << "zone " << z;
    if (eps[z] > 0 && sigma > yield * (1 - 1e-12)) ++on_surface;
    largest_eps = std::max(largest_eps, eps[z]);
  }
  EXPECT_GT(largest_eps, 0.3);
  EXPECT_GT(on_surface, 0);

  NamedValues errors, diagnostics;
  reference(sim, errors, diagnostics);
  const auto y = sim.y();
  EXPECT_NEAR(*std::min_element(y.begin(), y.end()), 0.0, 1e-15);  // the face stays on the wall
  const double length = value_of(diagnostics, "final_length");
  EXPECT_LT(length, 0.0324 - 1e-3);  // 227 m/s for 12 us: less than 2.7 mm shorter
  EXPECT_GT(length, 0.0324 - 2.7e-3);
  // The axis is x = 0, so the face's extent is its radius: it has mushroomed.
  EXPECT_GT(value_of(diagnostics, "impact_face_width"), 0.0032 * 1.2);
}

TEST(RzStrength, VerneyShellStopsAtTheSphericalRadii) {
  // 10 x 8 zones: the shell stops within 0.3 mm of the incompressible rigid-plastic radii.
  Scene s = scene("shell_rz", {{"mesh.refine", "0.5"}});
  const Reference reference = s.control.reference;
  Simulation sim(std::move(s.problem));
  sim.advance_to(sim.problem().t_end);
  NamedValues errors, diagnostics;
  reference(sim, errors, diagnostics);
  const double inner = value_of(diagnostics, "inner_radius"), outer = value_of(diagnostics, "outer_radius");
  const double inner_exact = value_of(diagnostics, "inner_stopping_radius_exact");
  const double outer_exact = value_of(diagnostics, "outer_stopping_radius_exact");
  std::printf("[ numbers  ] Verney shell 10x8: r_in %.4f (exact %.4f) r_out %.4f (exact %.4f) mm, asymmetry %.2e\n",
              1e3 * inner, 1e3 * inner_exact, 1e3 * outer, 1e3 * outer_exact, value_of(diagnostics, "asymmetry"));
  // The spherical radii, not the cylindrical ones (49.997 / 78.101 mm).
  EXPECT_NEAR(inner_exact, 0.0627078, 1e-6);
  EXPECT_NEAR(inner, inner_exact, 3e-4);
  EXPECT_NEAR(outer, outer_exact, 3e-4);
  EXPECT_LT(value_of(diagnostics, "kinetic_energy"), 3e-3 * sim.energy().initial);  // elastic ringing only
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger
