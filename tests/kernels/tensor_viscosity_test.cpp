// Tensor viscosity (docs/algorithm.md §4.1): the corner forces of one zone conserve momentum
// and angular momentum, vanish under rigid motion, only dissipate, reduce to the bulk q in
// one-dimensional compression; a Sedov run keeps its mirror symmetry about the diagonal and
// its energy audit at round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/kernels/viscosity_bulk.hpp"
#include "hydro/kernels/viscosity_tensor.hpp"
#include "stagger/meshgen.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {

// A convex polygon with n vertices on a squashed circle (counter-clockwise).
ZoneVertices polygon(int n) {
  ZoneVertices v;
  v.n = n;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n + 0.15 * std::sin(3.0 * k);
    v.x[k] = 0.3 + std::cos(a);
    v.y[k] = -0.2 + 0.6 * std::sin(a);
  }
  return v;
}

struct Forces {
  double fx[kMaxZoneVertices] = {}, fy[kMaxZoneVertices] = {};
  double q = 0;
};

Forces tensor_forces(const ZoneVertices& v, const double* ux, const double* uy) {
  Forces f;
  const double area = PlanarGeometry::area(v);
  f.q = add_tensor_viscosity_forces(v.n, v.x, v.y, ux, uy, area, PlanarGeometry::characteristic_length(v, area), 1.3,
                                    0.7, 1.5, 0.06, f.fx, f.fy);
  return f;
}

}  // namespace

TEST(TensorViscosity, RigidMotionFeelsNoForce) {
  for (int n : {3, 4, 5, 7}) {
    const ZoneVertices v = polygon(n);
    double ux[kMaxZoneVertices], uy[kMaxZoneVertices];
    for (int k = 0; k < n; ++k) {
      ux[k] = 0.4 - 0.9 * v.y[k];  // translation + rotation
      uy[k] = -0.3 + 0.9 * v.x[k];
    }
    const Forces f = tensor_forces(v, ux, uy);
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(f.fx[k], 0.0, 1e-15) << n;
      EXPECT_NEAR(f.fy[k], 0.0, 1e-15) << n;
    }
  }
}

TEST(TensorViscosity, ForcesAreOrthogonalToRigidMotionAndDissipate) {
  for (int n : {3, 4, 5, 7}) {
    const ZoneVertices v = polygon(n);
    double ux[kMaxZoneVertices], uy[kMaxZoneVertices];
    for (int k = 0; k < n; ++k) {  // compression with shear and noise
      ux[k] = -0.8 * v.x[k] + 0.3 * v.y[k] + 0.2 * std::sin(7.0 * k);
      uy[k] = -0.2 * v.y[k] + 0.1 * std::cos(5.0 * k + 1);
    }
    const Forces f = tensor_forces(v, ux, uy);
    double sx = 0, sy = 0, torque = 0, work = 0, scale = 0;
    for (int k = 0; k < n; ++k) {
      sx += f.fx[k];
      sy += f.fy[k];
      torque += v.x[k] * f.fy[k] - v.y[k] * f.fx[k];
      work += f.fx[k] * ux[k] + f.fy[k] * uy[k];
      scale += std::hypot(f.fx[k], f.fy[k]);
    }
    ASSERT_GT(scale, 0.05) << n;  // the zone compresses: real forces
    EXPECT_LT(std::abs(sx), 1e-14 * scale) << n;
    EXPECT_LT(std::abs(sy), 1e-14 * scale) << n;
    // Zero net force and torque: zero work under any rigid velocity added to the points.
    EXPECT_LT(std::abs(torque), 1e-14 * scale) << n;
    EXPECT_LT(work, -1e-3 * scale) << n;  // dissipative
    EXPECT_GT(f.q, 0.0) << n;
  }
}

TEST(TensorViscosity, ExpansionFeelsNoForce) {
  const ZoneVertices v = polygon(4);
  double ux[kMaxZoneVertices], uy[kMaxZoneVertices];
  for (int k = 0; k < 4; ++k) ux[k] = 0.5 * v.x[k], uy[k] = 0.2 * v.y[k];
  const Forces f = tensor_forces(v, ux, uy);
  EXPECT_EQ(f.q, 0.0);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(f.fx[k], 0.0);
    EXPECT_EQ(f.fy[k], 0.0);
  }
}

TEST(TensorViscosity, OneDimensionalCompressionIsTheBulkQ) {
  // A 0.2 x 0.1 rectangle compressed along x: the bulk q acting as a pressure on its sides.
  ZoneVertices v;
  v.n = 4;
  const double h = 0.2, d = 0.1;
  const double xs[] = {0, h, h, 0}, ys[] = {0, 0, d, d};
  double ux[4], uy[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; ++k) v.x[k] = xs[k], v.y[k] = ys[k], ux[k] = -3.0 * xs[k];
  const Forces f = tensor_forces(v, ux, uy);
  const double l = PlanarGeometry::characteristic_length(v, h * d);
  const double q = bulk_viscosity(1.3, l, -3.0, 0.7, 1.5, 0.06);
  EXPECT_NEAR(f.q, q, 1e-14 * q);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(f.fx[k], (xs[k] == 0 ? -1 : 1) * q * d / 2, 1e-14 * q) << k;
    EXPECT_NEAR(f.fy[k], 0.0, 1e-14 * q) << k;
  }
}

TEST(TensorViscosity, SedovKeepsItsMirrorSymmetryAndTheAuditAtRoundOff) {
  constexpr int n = 24;
  Problem p;
  p.name = "sedov";
  MeshBuildOptions options;
  p.mesh = build_mesh(meshgen::rectangle(0, 1.2, 0, 1.2, n, n), options);
  Material gas;
  gas.name = "gas";
  gas.eos = IdealGas{1.4};
  p.materials.push_back(gas);
  RegionSetup r;
  r.region = "domain";
  r.material = "gas";
  r.density = constant_field(1.0);
  r.specific_internal_energy = constant_field(1e-10);
  p.regions.push_back(r);
  for (const char* tag : {"left", "right", "bottom", "top"}) {
    BoundaryCondition bc;
    bc.tag = tag;
    p.boundaries.push_back(bc);
  }
  p.deposits.push_back({0, 0, 0.244816});
  p.options.viscosity = Viscosity::tensor;
  p.options.hourglass = Hourglass::subzonal_triangles;
  p.options.hourglass_coefficient = 2;
  p.t_end = 0.5;
  Simulation sim(std::move(p));
  sim.advance_to(0.5);
  ASSERT_GT(sim.cycle(), 100);
  // Zone (i, j) of the row-major grid mirrors zone (j, i) in the diagonal x = y.
  const auto rho = sim.density();
  double worst = 0, peak = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      worst = std::max(worst, std::abs(rho[j * n + i] - rho[i * n + j]) / rho[j * n + i]);
      peak = std::max(peak, rho[j * n + i]);
    }
  EXPECT_GT(peak, 2.0);  // a real shock
  EXPECT_LT(worst, 1e-11);
  EXPECT_LT(std::abs(sim.energy().relative_error), 1e-13);
}

}  // namespace stagger
