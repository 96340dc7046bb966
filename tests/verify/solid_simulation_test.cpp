// The solid and explosive references evaluated on a Simulation's initial state (no step taken).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"
#include "support/named_values.hpp"

namespace {

using stagger::testing::as_map;

stagger::Problem solid_problem(stagger::PolygonSoup soup, stagger::MieGruneisen eos, stagger::Strength strength,
                               stagger::RegionSetup setup, stagger::BoundaryKind kind) {
  stagger::Problem problem;
  problem.name = "verify_solid";
  problem.mesh = stagger::build_mesh(soup);
  stagger::Material material;
  material.name = "solid";
  material.eos = eos;
  material.strength = strength;
  problem.materials.push_back(material);
  setup.region = "domain";
  setup.material = "solid";
  problem.regions.push_back(setup);
  for (const auto& tag : problem.mesh.tags) {
    stagger::BoundaryCondition boundary;
    boundary.tag = tag.name;
    boundary.kind = kind;
    problem.boundaries.push_back(boundary);
  }
  problem.t_end = 1.0;
  return problem;
}

TEST(SolidReferences, ShellReferenceMeasuresTheInitialQuarterShell) {
  stagger::RegionSetup setup;
  setup.density = stagger::constant_field(1845.0);
  setup.pressure = stagger::constant_field(1e5);
  setup.velocity_x = [](double x, double y) { return -417.1 * 0.08 * x / (x * x + y * y); };
  setup.velocity_y = [](double x, double y) { return -417.1 * 0.08 * y / (x * x + y * y); };
  const stagger::Simulation simulation(
      solid_problem(stagger::meshgen::annulus_sector(0.08, 0.1, 0.0, std::numbers::pi / 2, 20, 16),
                    {1845.0, 12870.0, 2.0, 1.124}, {151.9e9, 330e6}, setup, stagger::BoundaryKind::free));
  stagger::NamedValues errors, diagnostics;
  stagger::be_shell_reference()(simulation, errors, diagnostics);
  const auto d = as_map(diagnostics);
  EXPECT_NEAR(d.at("inner_radius"), 0.08, 1e-14);
  EXPECT_NEAR(d.at("outer_radius"), 0.1, 1e-14);
  EXPECT_EQ(d.at("inner_radius_exact"), 0.08);
  EXPECT_LT(d.at("asymmetry"), 1e-14);
  // The sector's discrete kinetic energy against the analytic one scaled to a quarter: the
  // chords of the polygonal circles make the sector's mass slightly smaller; 1% is plenty.
  EXPECT_NEAR(d.at("kinetic_energy"), d.at("kinetic_energy_exact"), 0.01 * d.at("kinetic_energy_exact"));
  EXPECT_NEAR(d.at("kinetic_energy_exact"), stagger::HowellBallShell().kinetic_energy(0) / 4,
              0.01 * d.at("kinetic_energy_exact"));
}

TEST(SolidReferences, AccuracyReferenceVanishesOnTheExactInitialState) {
  const stagger::AccuracySolution exact;
  stagger::RegionSetup setup;
  setup.density = [&](double x, double y) { return exact.density(x, y, 0); };
  setup.specific_internal_energy = stagger::constant_field(1e-14);
  setup.velocity_x = stagger::constant_field(1e4);
  setup.velocity_y = stagger::constant_field(1e4);
  setup.stress_xx = [&](double x, double y) { return exact.stress_xx(x, y, 0); };
  setup.stress_yy = [&](double x, double y) { return exact.stress_yy(x, y, 0); };
  setup.stress_xy = [&](double x, double y) { return exact.stress_xy(x, y, 0); };
  auto problem = solid_problem(stagger::meshgen::rectangle(0, 1, 0, 1, 8, 8), {8930.0, 3940.0, 2.0, 1.49}, {45e9, 90e9},
                               setup, stagger::BoundaryKind::free);
  const stagger::Simulation simulation(std::move(problem));
  stagger::NamedValues errors, diagnostics;
  stagger::accuracy_reference()(simulation, errors, diagnostics);
  const auto e = as_map(errors);
  EXPECT_LT(e.at("L2_density"), 1e-9);
  for (const char* name : {"L2_deviatoric_stress_xx", "L2_deviatoric_stress_yy", "L2_deviatoric_stress_xy"})
    EXPECT_LT(e.at(name), 1e-6) << name;
}

TEST(SolidReferences, PistonFrontsAreTheMidJumpCrossings) {
  const stagger::ElasticPlasticPiston piston;
  const double ue = piston.elastic_state().velocity;
  stagger::RegionSetup setup;
  setup.density = stagger::constant_field(8930.0);
  setup.pressure = stagger::constant_field(1e5);
  // Points every 0.1 m: u = 20 up to x = 0.3, the elastic value at 0.4 ... 0.6, 0 beyond.
  setup.velocity_x = [&](double x, double) { return x < 0.35 ? 20.0 : (x < 0.65 ? ue : 0.0); };
  const stagger::Simulation simulation(solid_problem(stagger::meshgen::rectangle(0, 1, 0, 0.1, 10, 1),
                                                     {8930.0, 3940.0, 2.0, 1.49}, {45e9, 90e6}, setup,
                                                     stagger::BoundaryKind::free));
  stagger::NamedValues errors, diagnostics;
  stagger::piston_reference()(simulation, errors, diagnostics);
  const auto d = as_map(diagnostics);
  EXPECT_NEAR(d.at("elastic_front"), 0.65, 1e-12);
  EXPECT_NEAR(d.at("plastic_front"), 0.35, 1e-12);
  EXPECT_EQ(d.at("elastic_front_exact"), 0.0);  // t = 0
  const auto e = as_map(errors);
  EXPECT_NEAR(e.at("L1_density"), 0.0, 1e-9);
  EXPECT_NEAR(e.at("Linf_velocity"), 20.0, 1e-12);
  EXPECT_TRUE(e.count("L1_deviatoric_stress_xx"));
}

}  // namespace
