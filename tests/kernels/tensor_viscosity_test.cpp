// Tensor viscosity (docs/algorithm.md §4.1): the corner forces of one zone conserve momentum
// and angular momentum, vanish under rigid motion, only dissipate, reduce to the bulk q in
// one-dimensional compression. A Sedov run with it: tests/step/tensor_viscosity_run_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "hydro/kernels/viscosity_bulk.hpp"
#include "hydro/kernels/viscosity_tensor.hpp"

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

}  // namespace stagger
