// Axisymmetric (rz) geometry (docs/algorithm.md §19): total energy to round-off with strength,
// edge viscosity and applied pressure, the axis condition, the set-up error for a negative
// radius. The kernels (volumes, hoop stress) are tested in tests/kernels/rz_kernels_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "problems.hpp"
#include "stagger/error.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
using namespace testing;

namespace {

// A strong, sheared, hoop-straining flow of an elastic-plastic gas on a perturbed quarter
// [0, 1]^2 of the (r, z) plane: the axis on x = 0, a wall at z = 0, the rest free.
Problem rz_strength_problem(double t_end) {
  Mesh mesh = rectangle_mesh(1.0, 1.0, 12, 12);
  perturb_interior(mesh, 1.0 / 12, 1.0 / 12, 0.25, 3);
  Problem p = gas_problem(std::move(mesh), 1.4, t_end);
  p.materials[0].strength = Strength{2.0, 0.4};
  RegionSetup r = uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double y) { return 0.4 * x * (1 - 0.5 * y); };
  r.velocity_y = [](double x, double y) { return -0.3 * std::sin(M_PI * y) * (1 + x); };
  p.regions.push_back(r);
  walls(p, {"bottom"});
  p.options.geometry = CoordinateSystem::rz;
  p.options.hourglass = Hourglass::flanagan_belytschko;
  p.options.hourglass_coefficient = 0.5;
  return p;
}

}  // namespace

TEST(Rz, TotalEnergyIsExactWithStrengthAndTheAxisKeepsZeroRadialVelocity) {
  Simulation sim(rz_strength_problem(0.1));
  int axis_checks = 0;
  sim.set_observer([&](const Simulation& s) {
    for (std::size_t p = 0; p < s.x().size(); ++p)
      if (s.x()[p] == 0) {
        EXPECT_EQ(s.velocity_x()[p], 0.0) << "axis point " << p;
        ++axis_checks;
      }
  });
  sim.advance_to(0.1);
  EXPECT_GT(sim.cycle(), 20);
  EXPECT_GT(axis_checks, 13 * 20);  // 13 axis points every cycle
  // The flow did something: stress and plastic flow appeared.
  double largest_plastic = 0;
  for (double eps : sim.plastic_strain()) largest_plastic = std::max(largest_plastic, eps);
  EXPECT_GT(largest_plastic, 1e-3);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

TEST(Rz, EdgeViscosityAndAppliedPressureKeepTheAuditExact) {
  Problem p = rz_strength_problem(0.05);
  p.materials[0].strength.reset();
  p.options.viscosity = Viscosity::edge;
  p.boundaries.push_back(boundary("right", BoundaryKind::pressure));
  p.boundaries.back().pressure = [](double t) { return 2.0 + 10 * t; };
  Simulation sim(std::move(p));
  sim.advance_to(0.05);
  EXPECT_GT(std::abs(sim.energy().boundary_work), 1e-3);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

TEST(Rz, ANegativeRadiusIsASetUpErrorNamingThePoint) {
  Mesh mesh = build_mesh(meshgen::rectangle(-0.5, 1.0, 0, 1.0, 6, 4));
  Problem p = gas_problem(std::move(mesh), 1.4, 0.1);
  p.regions.push_back(uniform_region(1.0, 1.0));
  p.options.geometry = CoordinateSystem::rz;
  try {
    Simulation sim(std::move(p));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("negative radius"), std::string::npos) << what;
    EXPECT_NE(what.find("point 0 (-0.5, 0)"), std::string::npos) << what;
  }
}

TEST(Rz, AleKeepsTheAuditExactAndTheAxisPointsOnTheAxis) {
  // The strength problem above with the ALE phase remapping after every cycle (docs/ale.md,
  // "ALE in rz"): total energy stays exact, the axis points stay on x = 0 with v_r = 0.
  Problem p = rz_strength_problem(0.05);
  p.ale.mode = AleMode::ale;
  p.ale.remap_every = 1;
  Simulation sim(std::move(p));
  std::vector<char> axis(sim.x().size());
  for (std::size_t q = 0; q < axis.size(); ++q) axis[q] = sim.x()[q] == 0;
  sim.advance_to(0.05);
  EXPECT_GT(sim.cycle(), 10);
  for (std::size_t q = 0; q < axis.size(); ++q)
    if (axis[q]) {
      EXPECT_EQ(sim.x()[q], 0.0) << "axis point " << q;
      EXPECT_EQ(sim.velocity_x()[q], 0.0) << "axis point " << q;
      EXPECT_EQ(sim.point_mass()[q], 0.0) << "axis point " << q;
    }
  EXPECT_GT(std::abs(sim.energy().ale_fixup), 0.0);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

// The point masses of docs/algorithm.md §19: r_p^0 times the planar median-dual mass, zero on
// the axis (a uniform 4 x 4 mesh of [0, 1]^2, rho = 2: interior planar dual mass 2 / 16).
TEST(Rz, PointMassIsTheRadiusTimesThePlanarMassAndZeroOnTheAxis) {
  Problem p = gas_problem(rectangle_mesh(1.0, 1.0, 4, 4), 1.4, 0.01);
  p.regions.push_back(uniform_region(2.0, 1.0));
  p.options.geometry = CoordinateSystem::rz;
  Simulation sim(std::move(p));
  int checked = 0;
  for (std::size_t q = 0; q < sim.x().size(); ++q) {
    const double x = sim.x()[q], y = sim.y()[q];
    const bool interior_y = y > 0 && y < 1;
    if (x == 0) {
      EXPECT_EQ(sim.point_mass()[q], 0.0) << "axis point " << q;
    } else if (x < 1 && interior_y) {
      EXPECT_NEAR(sim.point_mass()[q], x * 2.0 / 16, 1e-15) << "point " << q;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

// A spherically symmetric, non-uniform elastic-plastic compression of a shell (R in [1, 1.5],
// v = -0.3 / R^2 e_R, the pressurised gas pushing the outer rings out) on an equal-angle mesh
// of 12 angles x 6 rings, walls on z = 0 and the axis, free surfaces: every ring of points stays on one sphere to
// round-off. The deviator's in-plane tangential and hoop components stay equal (the hoop strain rate of
// docs/algorithm.md §19.1), so the hoop body force is radial; with D_thth = (1/V) dV/dt - (1/A) dA/dt the rings spread
// by about 1e-6 here.
TEST(Rz, SphericalElasticPlasticShellKeepsEveryRingOnASphere) {
  constexpr int kAngles = 12, kRings = 6;
  Problem p = gas_problem(build_mesh(meshgen::annulus_sector(1.0, 1.5, 0, M_PI / 2, kAngles, kRings)), 1.4, 0.2);
  p.materials[0].strength = Strength{20.0, 1.5, 2.0};
  RegionSetup r = uniform_region(1.0, 1.0);
  r.velocity_x = [](double x, double y) { return -0.3 * x / std::pow(x * x + y * y, 1.5); };
  r.velocity_y = [](double x, double y) { return -0.3 * y / std::pow(x * x + y * y, 1.5); };
  p.regions.push_back(r);
  walls(p, {"start", "end"});
  p.options.geometry = CoordinateSystem::rz;
  p.options.hourglass = Hourglass::gamma;
  p.options.hourglass_coefficient = 0.1;
  Simulation sim(std::move(p));
  std::vector<int> ring(sim.x().size());
  for (std::size_t q = 0; q < ring.size(); ++q)
    ring[q] = static_cast<int>(std::lround((std::hypot(sim.x()[q], sim.y()[q]) - 1.0) * kRings / 0.5));
  sim.advance_to(0.2);
  EXPECT_GT(sim.cycle(), 20);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  double largest_plastic = 0;
  for (double eps : sim.plastic_strain()) largest_plastic = std::max(largest_plastic, eps);
  EXPECT_GT(largest_plastic, 1e-3);
  std::vector<double> lo(kRings + 1, 1e300), hi(kRings + 1, 0);
  for (std::size_t q = 0; q < ring.size(); ++q) {
    const double radius = std::hypot(sim.x()[q], sim.y()[q]);
    lo[ring[q]] = std::min(lo[ring[q]], radius);
    hi[ring[q]] = std::max(hi[ring[q]], radius);
  }
  for (int i = 0; i <= kRings; ++i) {
    EXPECT_GT(std::abs(hi[i] - (1.0 + 0.5 * i / kRings)), 1e-3) << "ring " << i << " did not move";
    EXPECT_LT((hi[i] - lo[i]) / hi[i], 1e-10) << "ring " << i;
  }
}

// A spherical blast (Sedov, gamma = 1.4) on an equal-angle quarter disc of 8 angles x 24 rings
// with centre triangles: total energy to round-off, every ring of zones the same to round-off
// (spherical symmetry, the zones at the axis included), and the axis points moving as the
// points of their ring on z = 0 (their planar mass from the corners' radial stretch).
TEST(Rz, SphericalBlastKeepsSymmetryOnAnEqualAngleMesh) {
  constexpr int kAngles = 8, kRings = 24;
  Simulation sim(rz_blast_problem(kAngles, kRings));
  sim.advance_to(0.1);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
  // Zones are numbered ring by ring from the centre (kAngles per ring).
  const auto rho = sim.density();
  ASSERT_EQ(rho.size(), static_cast<std::size_t>(kAngles * kRings));
  double worst = 0, peak = 0;
  int peak_ring = 0;
  for (int ring = 0; ring < kRings; ++ring) {
    const auto first = rho.begin() + ring * kAngles, last = first + kAngles;
    const double lo = *std::min_element(first, last), hi = *std::max_element(first, last);
    worst = std::max(worst, (hi - lo) / hi);
    if (hi > peak) peak = hi, peak_ring = ring;
  }
  EXPECT_LT(worst, 1e-11);
  // The shock (exact radius 0.398 at t = 0.1) has reached rings 6 to 8 (spacing 0.05).
  EXPECT_GE(peak_ring, 6);
  EXPECT_LE(peak_ring, 8);
  EXPECT_GT(peak, 2.0);
  // Axis points (x = 0) against the points of z = 0 at the same radius.
  int compared = 0;
  for (std::size_t a = 0; a < sim.x().size(); ++a) {
    if (sim.x()[a] != 0 || sim.y()[a] == 0) continue;
    for (std::size_t b = 0; b < sim.x().size(); ++b)
      if (sim.y()[b] == 0 && std::abs(sim.x()[b] - sim.y()[a]) < 1e-6) {
        EXPECT_NEAR(sim.velocity_y()[a], sim.velocity_x()[b], 1e-12 + 1e-10 * std::abs(sim.velocity_x()[b]))
            << "axis point " << a << " against point " << b;
        ++compared;
      }
  }
  EXPECT_EQ(compared, kRings);
}

// An axially periodic cylinder (bottom z = 0 periodic with top z = 1, the axis a wall): the
// copies of an axis point carry no mass, and their periodic group's mass-weighted velocity was
// 0 / 0 = NaN at cycle 0 (the run then "tangled" at once). Now the copies share their mean
// velocity: the run completes, every partner pair moves alike and the audit is exact.
TEST(Rz, AnAxiallyPeriodicCylinderRunsAndItsPartnersMoveAlike) {
  Problem p = gas_problem(rectangle_mesh(1.0, 1.0, 10, 10), 1.4, 0.2);
  RegionSetup r = gas_region(constant_field(1.0));
  r.pressure = [](double x, double y) { return 1 + 0.5 * std::cos(2 * M_PI * y) * (1 - x); };
  p.regions.push_back(r);
  walls(p, {"left", "right"});
  p.boundaries.push_back(boundary("bottom", BoundaryKind::periodic));
  p.boundaries.back().partner = "top";
  p.options.geometry = CoordinateSystem::rz;
  Simulation sim(std::move(p));
  sim.advance_to(0.2);
  EXPECT_GT(sim.cycle(), 20);
  double largest = 0;
  for (std::size_t q = 0; q < sim.x().size(); ++q) {
    ASSERT_TRUE(std::isfinite(sim.velocity_x()[q]) && std::isfinite(sim.velocity_y()[q])) << "point " << q;
    largest = std::max(largest, std::abs(sim.velocity_y()[q]));
  }
  EXPECT_GT(largest, 1e-3);  // the flow did something
  // Point (i, 0) and (i, 10) of the 11 x 11 points are one point.
  const BoundaryTag& bottom = sim.mesh().tags[sim.mesh().tag_index("bottom")];
  const BoundaryTag& top = sim.mesh().tags[sim.mesh().tag_index("top")];
  ASSERT_EQ(bottom.points.size(), top.points.size());
  int axis_pairs = 0;
  for (Index b : bottom.points)
    for (Index t : top.points)
      if (sim.problem().mesh.x[b] == sim.problem().mesh.x[t]) {
        EXPECT_EQ(sim.velocity_x()[b], sim.velocity_x()[t]) << "points " << b << ", " << t;
        EXPECT_EQ(sim.velocity_y()[b], sim.velocity_y()[t]) << "points " << b << ", " << t;
        axis_pairs += sim.problem().mesh.x[b] == 0;
      }
  EXPECT_EQ(axis_pairs, 1);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-12);
}

// The axis x = 0 can take no velocity, pressure or periodic condition (it is the symmetry
// line; a velocity there broke the audit by 2.8 %, a pressure there did nothing), nor can a
// periodic pair translate in r: set-up errors naming the tag and the axis.
TEST(Rz, BoundaryConditionsThatCannotHoldOnTheAxisAreRefused) {
  const auto error_of = [](BoundaryKind kind, double x0) {
    Mesh mesh = build_mesh(meshgen::rectangle(x0, x0 + 1.0, 0, 1.0, 4, 4));
    Problem p = gas_problem(std::move(mesh), 1.4, 0.1);
    p.regions.push_back(uniform_region(1.0, 1.0));
    if (kind == BoundaryKind::periodic)
      walls(p, {"bottom", "top"});  // "right" is the partner
    else
      walls(p, {"right", "bottom", "top"});
    p.boundaries.push_back(boundary("left", kind));
    if (kind == BoundaryKind::periodic) p.boundaries.back().partner = "right";
    p.options.geometry = CoordinateSystem::rz;
    try {
      Simulation sim(std::move(p));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (BoundaryKind kind : {BoundaryKind::velocity, BoundaryKind::pressure, BoundaryKind::periodic}) {
    const std::string what = error_of(kind, 0.0);
    EXPECT_NE(what.find("boundary 'left' (type "), std::string::npos) << what;
    EXPECT_NE(what.find("the axis x = 0"), std::string::npos) << what;
  }
  const std::string radial = error_of(BoundaryKind::periodic, 0.5);
  EXPECT_NE(radial.find("only a translation along the axis (in y)"), std::string::npos) << radial;
  EXPECT_EQ(error_of(BoundaryKind::wall, 0.0), "no error");
  EXPECT_EQ(error_of(BoundaryKind::free, 0.0), "no error");
}

}  // namespace stagger
