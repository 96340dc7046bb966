// Linear isotropic hardening (docs/solids.md §7): a homogeneous uniaxial compression of the
// piston's copper, driven by its boundaries, where the discrete answer is known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "support/files.hpp"
#include "support/scene_toml.hpp"

namespace stagger {
namespace {

struct Compression {
  double mu = 0, yield0 = 0, hardening = 0;
  double strain = 0;  // ln(L0 / L) of the bar
  double eps_min = 1e300, eps_max = -1e300;
  double surface_error = 0;  // max |sigma_eq - (Y0 + H eps_p)| / Y0
  double sigma_eq = 0, audit = 0;
  long cycles = 0;
};

// The piston's copper (apps/scenes/piston.toml) on 10 x 2 zones, the piston's velocity field
// already set up inside the bar: v_x = u (1 - x) between the piston (x = 0, u = 20 m/s) and
// the wall (x = 1). With a linear velocity every zone deforms alike, the stress is uniform, the
// interior forces cancel and every point keeps its velocity: uniaxial strain at the rate u / L(t).
std::string scene_file() {
  namespace toml = testing::toml;
  const std::string scene = toml::time("500e-6") + toml::rectangle("[0.0, 1.0]", "[0.0, 0.1]", 10, 2) + toml::copper() +
                            "[material.strength]\nshear_modulus = 45e9\nyield_stress = 90e6\n" +
                            toml::region("copper", "8930.0", "1e5") + "velocity = [\"20 * (1 - x)\", 0.0]\n" +
                            "[[boundary]]\ntag = \"left\"\ntype = \"velocity\"\nvelocity = [20.0, 0.0]\n" +
                            toml::walls(R"(["right", "bottom", "top"])") + "[numerics]\ncfl = 0.1\n";
  return testing::write_text(::testing::TempDir() + "hardening_compression.toml", scene);
}

Compression compress(const std::string& hardening, double t_end) {
  std::vector<std::pair<std::string, std::string>> overrides{{"time.end", std::to_string(t_end)}};
  if (!hardening.empty()) overrides.emplace_back("material[0].strength.hardening_modulus", hardening);
  Scene scene = load_scene(scene_file(), overrides);
  Compression c;
  const auto& strength = std::get<LinearHardening>(*scene.problem.materials[0].strength);
  c.mu = strength.shear_modulus;
  c.yield0 = strength.yield_stress;
  c.hardening = strength.hardening_modulus;
  Simulation sim(std::move(scene.problem));
  sim.advance_to(t_end);
  c.cycles = sim.cycle();
  const auto x = sim.x();
  const double length = *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
  c.strain = std::log(1.0 / length);
  const auto sxx = sim.stress_xx(), syy = sim.stress_yy(), sxy = sim.stress_xy(), eps = sim.plastic_strain();
  for (std::size_t z = 0; z < eps.size(); ++z) {
    const double szz = -(sxx[z] + syy[z]);
    const double seq = std::sqrt(1.5 * (sxx[z] * sxx[z] + syy[z] * syy[z] + szz * szz + 2 * sxy[z] * sxy[z]));
    c.surface_error = std::max(c.surface_error, std::abs(seq - (c.yield0 + c.hardening * eps[z])) / c.yield0);
    c.eps_min = std::min(c.eps_min, eps[z]);
    c.eps_max = std::max(c.eps_max, eps[z]);
    c.sigma_eq = seq;
  }
  c.audit = sim.energy().relative_error;
  return c;
}

// The return of docs/algorithm.md §7 adds 2 mu |d| dt / (3 mu + H) per plastic step, so from
// yield on eps_p = (2 mu E - Y0) / (3 mu + H) with E = sum |d| dt, the midpoint rule for
// ln(L0 / L): the plastic strain and the hardened yield stress follow it to round-off.
void expect_closed_form(const Compression& c) {
  const double expected = (2 * c.mu * c.strain - c.yield0) / (3 * c.mu + c.hardening);
  std::printf(
      "[ numbers  ] H = %.3g: %ld cycles, strain %.6f, eps_p %.9e (closed form %.9e), sigma_eq %.6e, audit %.2e\n",
      c.hardening, c.cycles, c.strain, c.eps_max, expected, c.sigma_eq, c.audit);
  EXPECT_GT(expected, 0.003);                           // well into the plastic range
  EXPECT_LT(c.eps_max - c.eps_min, 1e-10 * c.eps_max);  // round-off over ~600 cycles
  EXPECT_NEAR(c.eps_max, expected, 1e-6 * expected);
  EXPECT_LT(c.surface_error, 1e-12);
  EXPECT_LT(std::abs(c.audit), 1e-12);
}

}  // namespace

TEST(LinearHardening, UniaxialCompressionFollowsTheHardenedYieldStress) {
  const Compression c = compress("45e9", 500e-6);
  expect_closed_form(c);
  // Hardening visibly at work: the flow stress has more than tripled.
  EXPECT_GT(c.sigma_eq, 3 * c.yield0);
}

TEST(LinearHardening, ZeroModulusIsPerfectlyPlasticAndBitwiseTheDefault) {
  const Compression zero = compress("0.0", 500e-6), unset = compress("", 500e-6);
  expect_closed_form(zero);
  EXPECT_NEAR(zero.sigma_eq, zero.yield0, 1e-12 * zero.yield0);
  EXPECT_EQ(zero.eps_max, unset.eps_max);
  EXPECT_EQ(zero.sigma_eq, unset.sigma_eq);
  EXPECT_EQ(zero.audit, unset.audit);
}

TEST(LinearHardening, NegativeModulusIsRejectedNamingTheKey) {
  try {
    load_scene(scene_file(), {{"material[0].strength.hardening_modulus", "-1e9"}});
    ADD_FAILURE() << "a negative hardening modulus was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("hardening_modulus"), std::string::npos) << e.what();
  }
}

}  // namespace stagger
