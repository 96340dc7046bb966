// Elastic-plastic solids (docs/solids.md §1-2): the copper piston's two waves, the beryllium shell's
// stopping radius and symmetry, and the energy audit at round-off in both.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"
#include "support/copper.hpp"
#include "support/gas_problem.hpp"
#include "support/named_values.hpp"

namespace stagger {

namespace {
using testing::boundary;
using testing::value_of;
}  // namespace

TEST(ElasticPlasticPiston, BothWavesWithinTwoPercentAndEnergyAtRoundOff) {
  Problem p;
  p.name = "piston";
  p.mesh = build_mesh(meshgen::rectangle(0, 1, 0, 0.1, 100, 5));
  p.materials.push_back(testing::piston_copper());
  RegionSetup r;
  r.region = "domain";
  r.material = "copper";
  r.density = constant_field(8930.0);
  r.pressure = constant_field(1e5);
  p.regions.push_back(r);
  BoundaryCondition piston = boundary("left", BoundaryKind::velocity);
  piston.velocity_x = constant_in_time(20.0);
  p.boundaries = {piston, boundary("right", BoundaryKind::wall), boundary("bottom", BoundaryKind::wall),
                  boundary("top", BoundaryKind::wall)};
  p.options.cfl = 0.1;
  p.t_end = 150e-6;
  Simulation sim(std::move(p));
  sim.advance_to(150e-6);
  NamedValues errors, diagnostics;
  piston_reference()(sim, errors, diagnostics);
  const double elastic = value_of(diagnostics, "elastic_front"),
               elastic_exact = value_of(diagnostics, "elastic_front_exact");
  const double plastic = value_of(diagnostics, "plastic_front"),
               plastic_exact = value_of(diagnostics, "plastic_front_exact");
  std::printf("piston 100x5: cycles %ld elastic %.4f (exact %.4f) plastic %.4f (exact %.4f) audit %.2e\n", sim.cycle(),
              elastic, elastic_exact, plastic, plastic_exact, sim.energy().relative_error);
  EXPECT_NEAR(elastic / elastic_exact, 1.0, 0.02);
  EXPECT_NEAR(plastic / plastic_exact, 1.0, 0.02);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  // On the yield surface |S_xx| = 2Y/3 = 60 MPa (S_zz kept in the von Mises norm; a 2D
  // trace-free deviator would give 51.96 MPa), never above it.
  double largest = 0;
  for (double sxx : sim.stress_xx()) largest = std::max(largest, std::abs(sxx));
  EXPECT_NEAR(largest, 60e6, 60e6 * 1e-9);
}

TEST(BerylliumShell, StopsWithinAMillimetreOfHowellBallAndStaysSymmetric) {
  Problem p;
  p.name = "be_shell";
  p.mesh = build_mesh(meshgen::annulus_sector(0.08, 0.1, 0, M_PI / 2, 20, 16));
  Material be;
  be.name = "beryllium";
  be.eos = MieGruneisen{1845.0, 12870.0, 2.0, 1.124};
  be.strength = Strength{151.9e9, 330e6};
  p.materials.push_back(be);
  RegionSetup r;
  r.region = "domain";
  r.material = "beryllium";
  r.density = constant_field(1845.0);
  r.pressure = constant_field(1e5);
  r.velocity_x = [](double x, double y) { return -417.1 * 0.08 * x / (x * x + y * y); };
  r.velocity_y = [](double x, double y) { return -417.1 * 0.08 * y / (x * x + y * y); };
  p.regions.push_back(r);
  p.boundaries = {boundary("start", BoundaryKind::wall), boundary("end", BoundaryKind::wall),
                  boundary("inner", BoundaryKind::free), boundary("outer", BoundaryKind::free)};
  p.options.cfl = 0.1;
  // The shell's own numerics (apps/scenes/be_shell.toml): the bulk q and the gamma force keep
  // its rotational symmetry at round-off (docs/algorithm.md §4.2).
  p.options.viscosity = Viscosity::bulk;
  p.options.hourglass = Hourglass::gamma;
  p.options.hourglass_coefficient = 0.1;
  p.t_end = 130e-6;
  Simulation sim(std::move(p));
  sim.advance_to(130e-6);
  NamedValues errors, diagnostics;
  be_shell_reference()(sim, errors, diagnostics);
  const double inner = value_of(diagnostics, "inner_radius"), exact = value_of(diagnostics, "inner_radius_exact");
  const double asym = value_of(diagnostics, "asymmetry");
  std::printf("be shell 20x16: cycles %ld inner %.5f mm (exact %.5f) outer %.5f mm asymmetry %.2e audit %.2e\n",
              sim.cycle(), inner * 1e3, exact * 1e3, value_of(diagnostics, "outer_radius") * 1e3, asym,
              sim.energy().relative_error);
  EXPECT_NEAR(inner, exact, 1e-3);
  EXPECT_LT(asym, 1e-12);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

}  // namespace stagger

// ---- Scenes through load_scene: the gmsh Be shell, the piston's plastic plateau. ----
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "stagger/scene.hpp"

namespace stagger {
namespace {
std::string scene_path(const char* name) {
  return std::string(STAGGER_SOURCE_DIR) + "/apps/scenes/" + name;
}
}  // namespace

// apps/scenes/be_shell.toml as shipped: the gmsh quarter shell (geometries/quarter_shell.geo),
// 20x16. With gmsh's own spacing of a transfinite Circle the node angles were equal only to
// 2.4e-9 rad and the asymmetry was 9.4e-11; the .geo now places every boundary node
// explicitly and the mesh is equal-angle to round-off (docs/solids.md).
TEST(BerylliumShell, GmshSceneStopsWithinAMillimetreAndStaysSymmetricToRoundOff) {
  Scene scene = load_scene(scene_path("be_shell.toml"));
  const Reference reference = scene.control.reference;
  ASSERT_TRUE(reference);
  ASSERT_EQ(scene.problem.mesh.num_zones(), 320);
  Simulation sim(std::move(scene.problem));
  sim.advance_to(130e-6);
  NamedValues errors, diagnostics;
  reference(sim, errors, diagnostics);
  const double inner = value_of(diagnostics, "inner_radius"), exact = value_of(diagnostics, "inner_radius_exact");
  const double outer = value_of(diagnostics, "outer_radius"), outer_exact = value_of(diagnostics, "outer_radius_exact");
  const double asym = value_of(diagnostics, "asymmetry");
  std::printf(
      "[ numbers  ] be_shell.toml 20x16 (gmsh): cycles %ld inner %.5f mm (exact %.5f) outer %.5f mm (exact %.5f) "
      "asymmetry %.2e audit %.2e\n",
      sim.cycle(), inner * 1e3, exact * 1e3, outer * 1e3, outer_exact * 1e3, asym, sim.energy().relative_error);
  EXPECT_NEAR(inner, exact, 1e-3);
  EXPECT_NEAR(outer, outer_exact, 1e-3);
  EXPECT_LT(asym, 1e-12);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  // The kinetic energy has become plastic heat: what is left is the elastic ringing.
  EXPECT_LT(value_of(diagnostics, "kinetic_energy"), 1e-3 * sim.energy().initial);
}

// Behind the plastic shock the exact S_xx is -2Y/3 = -60 MPa. The scheme's post-shock density
// overshoot relaxes and unloads some zones elastically (dS_xx = (4 mu / 3) d ln(rho0 / rho):
// 1e-4 in density is 6 MPa), so the coarse plateau sits at -44 .. -60 MPa; the deviation
// shrinks with refinement (measured, mean over the plateau: 4.1, 1.4, 0.37, 0.074 MPa at
// 100, 200, 400, 800 x 5) and the yield surface is never exceeded.
TEST(ElasticPlasticPiston, PlasticPlateauStressConvergesToTheYieldValue) {
  std::vector<double> mean_deviation;
  for (int nx : {100, 200, 400}) {
    Scene scene = load_scene(scene_path("piston.toml"), {{"mesh.nx", std::to_string(nx)}});
    const Reference reference = scene.control.reference;
    Simulation sim(std::move(scene.problem));
    sim.advance_to(150e-6);
    NamedValues errors, diagnostics;
    reference(sim, errors, diagnostics);
    const double plastic_exact = value_of(diagnostics, "plastic_front_exact");
    const auto cx = zone_centres(sim.mesh(), sim.x(), sim.y())[0];
    double lo = 1e300, hi = -1e300, deviation = 0, area = 0;
    int off = 0, plateau = 0;
    for (std::size_t z = 0; z < cx.size(); ++z) {
      if (cx[z] < 0.05 || cx[z] > plastic_exact - 0.05) continue;
      const double s = sim.stress_xx()[z];
      lo = std::min(lo, s), hi = std::max(hi, s);
      deviation += std::abs(s + 60e6) * sim.zone_area()[z], area += sim.zone_area()[z];
      off += std::abs(s + 60e6) > 1e6;
      ++plateau;
    }
    mean_deviation.push_back(deviation / area);
    std::printf(
        "[ numbers  ] piston %dx5: plateau S_xx in [%.2f, %.2f] MPa, mean |S_xx + 60 MPa| %.3f MPa, %d of %d "
        "zones more than 1 MPa off; L1_deviatoric_stress_xx %.3e\n",
        nx, lo / 1e6, hi / 1e6, deviation / area / 1e6, off, plateau, value_of(errors, "L1_deviatoric_stress_xx"));
    EXPECT_GE(lo, -60e6 * (1 + 1e-9));  // radial return: never beyond the yield surface
  }
  EXPECT_LT(mean_deviation[1], 0.5 * mean_deviation[0]);
  EXPECT_LT(mean_deviation[2], 0.5 * mean_deviation[1]);
  EXPECT_LT(mean_deviation[2], 1e6);
}

}  // namespace stagger
