// High explosives (docs/solids.md §3): the paper's planar Comp B detonation (apps/scenes/detonation.toml,
// cm-g-us) on coarse meshes against the CJ + Taylor-wave solution (verify.hpp CJDetonation),
// the programmed burn's fraction, and the HE slab driving a copper plate (he_plate.toml).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "stagger/scene.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

std::string scene_path(const char* name) {
  return std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/" + name;
}

double lookup(const NamedValues& values, const std::string& name) {
  for (const auto& [key, value] : values)
    if (key == name) return value;
  ADD_FAILURE() << "no value named " << name;
  return NAN;
}

Simulation load(const char* scene, const Overrides& overrides) {
  Scene s = load_scene(scene_path(scene), overrides);
  return Simulation(std::move(s.problem));
}

}  // namespace

// 200 x 1 zones (dx = 0.005 cm), t = 1 us: the front, the plateau at the wall and the audit.
// The programmed burn puts the half-P_CJ point about 1.2 zones behind D t (1.6% at 100 zones,
// 0.75% at 200: first order in dx), hence 200 zones for a 2% test with a margin.
TEST(PlanarDetonation, FrontPlateauAndEnergyOnACoarseMesh) {
  Scene scene = load_scene(scene_path("detonation.toml"), {{"mesh.nx", "200"}, {"mesh.ny", "1"}});
  const Reference reference = scene.control.reference;
  ASSERT_TRUE(reference);
  Simulation sim(std::move(scene.problem));
  sim.advance_to(1.0);
  NamedValues errors, diagnostics;
  reference(sim, errors, diagnostics);
  const double front = lookup(diagnostics, "front_position"), front_exact = lookup(diagnostics, "front_position_exact");
  const double plateau = lookup(diagnostics, "plateau_pressure");
  const double plateau_exact = lookup(diagnostics, "plateau_pressure_exact");
  const double peak = lookup(diagnostics, "peak_pressure"), cj = lookup(diagnostics, "cj_pressure_exact");
  std::printf(
      "[ numbers  ] detonation 200x1: cycles %ld front %.5f (D t %.5f, nominal %.5f) plateau %.6f (exact %.6f) "
      "peak %.4f (P_CJ %.4f) L1_pressure %.3e audit %.2e\n",
      sim.cycle(), front, front_exact, lookup(diagnostics, "front_position_nominal"), plateau, plateau_exact, peak, cj,
      lookup(errors, "L1_pressure"), sim.energy().relative_error);
  EXPECT_NEAR(front / front_exact, 1.0, 0.02);
  EXPECT_NEAR(plateau / plateau_exact, 1.0, 0.02);
  // The chemical energy is in e from t = 0: burning only converts it, so E is constant.
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  EXPECT_EQ(sim.energy().boundary_work, 0.0);
  // The peak is smeared below P_CJ (no von Neumann spike in a programmed burn), but not far.
  EXPECT_GT(peak, 0.9 * cj);
  EXPECT_LT(peak, 1.05 * cj);
}

// The pressure profile follows the self-similar Taylor wave at several times: L1 of pressure
// over the burnt products is a few percent of P_CJ at every dump time, and the plateau holds.
TEST(PlanarDetonation, PressureProfileFollowsTheTaylorWaveAtSeveralTimes) {
  Scene scene = load_scene(scene_path("detonation.toml"), {{"mesh.nx", "100"}, {"mesh.ny", "1"}});
  const Reference reference = scene.control.reference;
  Simulation sim(std::move(scene.problem));
  const CJDetonation exact;
  for (double t : {0.4, 0.6, 0.8, 1.0}) {
    sim.advance_to(t);
    NamedValues errors, diagnostics;
    reference(sim, errors, diagnostics);
    const double l1 = lookup(errors, "L1_pressure");
    const double plateau = lookup(diagnostics, "plateau_pressure");
    std::printf(
        "[ numbers  ] t = %.1f us: L1_pressure %.3e Mbar (%.2f%% of P_CJ over the bar), plateau %.6f, front %.4f "
        "(D t %.4f)\n",
        t, l1, 100 * l1 / exact.cj_state().pressure, plateau, lookup(diagnostics, "front_position"),
        exact.cj_speed() * t);
    // L1 is over the whole bar (1 cm), most of it unburnt and exact: scale by the burnt part.
    EXPECT_LT(l1 / (exact.cj_speed() * t), 0.05 * exact.cj_state().pressure) << "t = " << t;
    EXPECT_NEAR(plateau / exact.plateau_pressure(), 1.0, 0.02) << "t = " << t;
  }
}

// Burn fraction in [0, 1], never decreasing in any zone, recorded every cycle; 1 behind the
// front, 0 well ahead of it.
TEST(ProgrammedBurn, FractionNeverDecreasesAndIsOneBehindTheFront) {
  Simulation sim = load(
      "detonation.toml",
      {{"mesh.nx", "40"}, {"mesh.ny", "2"}, {"mesh.x", "[0.0, 0.4]"}, {"mesh.y", "[0.0, 0.02]"}, {"time.end", "0.4"}});
  ASSERT_TRUE(sim.has_burn());
  std::vector<double> previous(sim.burn_fraction().begin(), sim.burn_fraction().end());
  for (double f : previous) EXPECT_EQ(f, 0.0);
  long decreases = 0, out_of_range = 0, observed = 0;
  sim.set_observer([&](const Simulation& s) {
    const auto burn = s.burn_fraction();
    for (std::size_t z = 0; z < burn.size(); ++z) {
      if (burn[z] < previous[z]) ++decreases;
      if (!(burn[z] >= 0.0 && burn[z] <= 1.0)) ++out_of_range;
      previous[z] = burn[z];
    }
    ++observed;
  });
  sim.advance_to(0.4);
  EXPECT_EQ(observed, sim.cycle());
  EXPECT_EQ(decreases, 0);
  EXPECT_EQ(out_of_range, 0);
  // Lighting at the zone centre at x / D, full burn 1.5 zone widths (LS-DYNA's 3 V / (2 A_max))
  // later: every zone whose centre the front passed more than 2 widths ago is fully burnt.
  const double front = 0.798 * 0.4, dx = 0.01;
  const auto burn = sim.burn_fraction();
  const auto cx = zone_centres(sim.mesh(), sim.problem().mesh.x, sim.problem().mesh.y)[0];
  int behind = 0, ahead = 0;
  for (std::size_t z = 0; z < burn.size(); ++z) {
    if (cx[z] < front - 2 * dx) {
      EXPECT_EQ(burn[z], 1.0) << "zone " << z << " at x0 = " << cx[z];
      ++behind;
    }
    if (cx[z] > front + dx) {
      EXPECT_EQ(burn[z], 0.0) << "zone " << z << " at x0 = " << cx[z];
      ++ahead;
    }
  }
  EXPECT_GT(behind, 40);
  EXPECT_GT(ahead, 10);
}

// HE slab (Comp B, programmed burn) next to a copper plate (Mie-Gruneisen + strength) in one
// mesh with two regions: runs with the audit at round-off, the plate is pushed forward,
// yields, and the copper never burns.
TEST(HePlate, DetonationDrivesTheCopperPlateWithEnergyAtRoundOff) {
  Scene scene = load_scene(scene_path("he_plate.toml"), {{"time.end", "1.5"}});
  Simulation sim(std::move(scene.problem));
  ASSERT_TRUE(sim.has_burn());
  ASSERT_TRUE(sim.has_strength());
  sim.advance_to(1.5);
  const Mesh& mesh = sim.mesh();
  const Index copper = mesh.region_index("plate");
  ASSERT_GE(copper, 0);
  // Mean x velocity of the plate's points (those of its zones), its yield and its burn factor.
  std::vector<char> in_plate(mesh.num_points(), 0);
  double plastic = 0, burn_min = 1;
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    if (mesh.zone_region[z] != copper) continue;
    for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c)
      in_plate[mesh.corner_point[c]] = 1;
    plastic = std::max(plastic, sim.plastic_strain()[z]);
    burn_min = std::min(burn_min, sim.burn_fraction()[z]);
  }
  double momentum = 0, mass = 0;
  for (Index p = 0; p < mesh.num_points(); ++p)
    if (in_plate[p]) momentum += sim.point_mass()[p] * sim.velocity_x()[p], mass += sim.point_mass()[p];
  const EnergyAudit audit = sim.energy();
  std::printf(
      "[ numbers  ] he_plate: cycles %ld plate mean u %.4f cm/us, max plastic strain %.3e, audit %.2e "
      "(E0 %.5e, KE %.5e)\n",
      sim.cycle(), momentum / mass, plastic, audit.relative_error, audit.initial, audit.kinetic);
  EXPECT_LT(std::abs(audit.relative_error), 1e-12);
  EXPECT_GT(momentum / mass, 0.01);  // pushed forward (+x), at a fair fraction of u_CJ
  EXPECT_GT(plastic, 0.0);           // 30 GPa shock: far beyond Y = 90 MPa
  EXPECT_EQ(burn_min, 1.0);          // inert zones carry the factor 1
}

}  // namespace stagger
