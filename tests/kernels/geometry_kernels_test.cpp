// The geometry policy and the force kernels alone, against values derived from their
// definitions (docs/algorithm.md §2, §4-§6): nothing here is a number typed in from a run.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "hydro/kernels/corner_forces.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/hourglass.hpp"
#include "hydro/kernels/time_step.hpp"
#include "hydro/kernels/viscosity_bulk.hpp"
#include "hydro/kernels/viscosity_edge.hpp"

namespace stagger {

namespace {

using G = PlanarGeometry;

ZoneVertices make(std::initializer_list<std::array<double, 2>> points) {
  ZoneVertices v;
  for (const auto& p : points) {
    v.x[v.n] = p[0];
    v.y[v.n] = p[1];
    ++v.n;
  }
  return v;
}

// A skewed, non-parallelogram convex quad (counter-clockwise).
ZoneVertices skewed_quad() {
  return make({{0.1, -0.2}, {1.3, 0.15}, {1.05, 1.2}, {-0.25, 0.8}});
}

// Area as the sum of the fan triangles (0, k, k+1), each 1/2 the cross product.
double fan_area(const ZoneVertices& v) {
  double a = 0;
  for (int k = 1; k + 1 < v.n; ++k)
    a += 0.5 * ((v.x[k] - v.x[0]) * (v.y[k + 1] - v.y[0]) - (v.x[k + 1] - v.x[0]) * (v.y[k] - v.y[0]));
  return a;
}

// Velocities of the linear field u = c + L x at the vertices.
void linear_field(const ZoneVertices& v, const double c[2], const double L[2][2], double* ux, double* uy) {
  for (int k = 0; k < v.n; ++k) {
    ux[k] = c[0] + L[0][0] * v.x[k] + L[0][1] * v.y[k];
    uy[k] = c[1] + L[1][0] * v.x[k] + L[1][1] * v.y[k];
  }
}

}  // namespace

TEST(GeometryKernels, AreaAndCentreOfASkewedQuadAndAPentagon) {
  for (const ZoneVertices& v : {skewed_quad(), make({{0, 0}, {2, -0.3}, {2.4, 1.1}, {1.1, 2.2}, {-0.4, 1.0}})}) {
    EXPECT_NEAR(G::area(v), fan_area(v), 1e-15);
    EXPECT_DOUBLE_EQ(G::area<0>(v), 0.5 * polygon_twice_area(
                                              v.n, [&](int k) { return v.x[k]; }, [&](int k) { return v.y[k]; }));
    double sx = 0, sy = 0;
    for (int k = 0; k < v.n; ++k) sx += v.x[k], sy += v.y[k];
    const auto [cx, cy] = G::centre(v);
    EXPECT_EQ(cx, sx / v.n);
    EXPECT_EQ(cy, sy / v.n);
  }
  // Clockwise: the same magnitude, negative.
  const ZoneVertices cw = make({{-0.25, 0.8}, {1.05, 1.2}, {1.3, 0.15}, {0.1, -0.2}});
  EXPECT_NEAR(G::area(cw), -fan_area(skewed_quad()), 1e-15);
}

TEST(GeometryKernels, CornerGradientsAreTheAreaDerivatives) {
  const ZoneVertices v = skewed_quad();
  double ax[4], ay[4];
  G::corner_gradients<4>(v, ax, ay);
  // The shoelace area is linear in each coordinate, so the central difference with any step
  // is the exact derivative dA/dx_k.
  for (int k = 0; k < 4; ++k) {
    ZoneVertices p = v, m = v;
    p.x[k] += 0.5, m.x[k] -= 0.5;
    EXPECT_NEAR(ax[k], G::area(p) - G::area(m), 1e-14) << k;
    p = v, m = v;
    p.y[k] += 0.5, m.y[k] -= 0.5;
    EXPECT_NEAR(ay[k], G::area(p) - G::area(m), 1e-14) << k;
  }
  // Their sum is zero (a translation does not change the area).
  EXPECT_NEAR(ax[0] + ax[1] + ax[2] + ax[3], 0, 1e-15);
  EXPECT_NEAR(ay[0] + ay[1] + ay[2] + ay[3], 0, 1e-15);
  // The gradient of a linear field is exact on any quad; div is its trace.
  const double c[2] = {0.3, -0.7}, L[2][2] = {{0.4, -1.3}, {2.1, -0.9}};
  double ux[4], uy[4];
  linear_field(v, c, L, ux, uy);
  const double A = G::area<4>(v);
  const VelocityGradient g = G::velocity_gradient(4, ux, uy, ax, ay, A);
  EXPECT_NEAR(g.xx, L[0][0], 1e-14);
  EXPECT_NEAR(g.xy, L[0][1], 1e-14);
  EXPECT_NEAR(g.yx, L[1][0], 1e-14);
  EXPECT_NEAR(g.yy, L[1][1], 1e-14);
  EXPECT_NEAR(G::divergence(4, ux, uy, ax, ay, A), L[0][0] + L[1][1], 1e-14);
}

TEST(GeometryKernels, CornerAreasAndCharacteristicLength) {
  // Corner areas partition the zone; on a parallelogram each is a quarter.
  const ZoneVertices v = skewed_quad();
  double ca[4];
  const double smallest = G::corner_areas<4>(v, ca);
  EXPECT_NEAR(ca[0] + ca[1] + ca[2] + ca[3], G::area(v), 1e-15);
  EXPECT_EQ(smallest, std::min({ca[0], ca[1], ca[2], ca[3]}));
  const ZoneVertices par = make({{0, 0}, {2, 0.5}, {2.7, 1.5}, {0.7, 1.0}});
  G::corner_areas<4>(par, ca);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(ca[k], G::area(par) / 4, 1e-15);
  // Corner k as its own polygon (x_k, mid(k,k+1), centre, mid(k-1,k)).
  G::corner_areas<4>(v, ca);
  const auto [cx, cy] = G::centre(v);
  for (int k = 0; k < 4; ++k) {
    const int kp = (k + 1) % 4, km = (k + 3) % 4;
    const ZoneVertices corner = make({{v.x[k], v.y[k]},
                                      {0.5 * (v.x[k] + v.x[kp]), 0.5 * (v.y[k] + v.y[kp])},
                                      {cx, cy},
                                      {0.5 * (v.x[k] + v.x[km]), 0.5 * (v.y[k] + v.y[km])}});
    EXPECT_NEAR(ca[k], fan_area(corner), 1e-15);
  }
  // l = A / longest diagonal: a square of side s has l = s / sqrt(2).
  const double s = 0.3;
  const ZoneVertices sq = make({{0, 0}, {s, 0}, {s, s}, {0, s}});
  EXPECT_NEAR(G::characteristic_length<4>(sq, G::area(sq)), s / std::sqrt(2.0), 1e-16);
  // A triangle: A / longest side.
  const ZoneVertices tri = make({{0, 0}, {3, 0}, {0, 4}});
  EXPECT_NEAR(G::characteristic_length<0>(tri, G::area(tri)), 6.0 / 5.0, 1e-15);
}

TEST(ForceKernels, StressCornerForcesOfAPressureOnASquare) {
  // f_c = -sigma a_c = P a_c for sigma = -P I: outward, P s/2 per component, summing to zero.
  const double s = 2.0, P = 3.0;
  const ZoneVertices sq = make({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  double ax[4], ay[4], fx[4], fy[4];
  G::corner_gradients<4>(sq, ax, ay);
  stress_corner_forces(4, Deviator{}, P, ax, ay, fx, fy);
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(fx[k], P * s / 2 * (sq.x[k] > 0 ? 1 : -1));
    EXPECT_DOUBLE_EQ(fy[k], P * s / 2 * (sq.y[k] > 0 ? 1 : -1));
  }
  // A pure shear deviator S_xy pushes the corners along the tangential directions.
  stress_corner_forces(4, Deviator{0, 0, 1.5}, 0, ax, ay, fx, fy);
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(fx[k], -1.5 * ay[k]);
    EXPECT_DOUBLE_EQ(fy[k], -1.5 * ax[k]);
  }
}

TEST(ForceKernels, BulkViscosityOnUniformCompression) {
  // u = -eps x on a square of side s: div u = -2 eps, l = s / sqrt(2).
  const double s = 0.5, eps = 0.8, rho = 2.0, C = 1.7, q1 = 1.5, q2 = 0.06;
  const ZoneVertices sq = make({{0, 0}, {s, 0}, {s, s}, {0, s}});
  double ax[4], ay[4], ux[4], uy[4];
  G::corner_gradients<4>(sq, ax, ay);
  for (int k = 0; k < 4; ++k) ux[k] = -eps * sq.x[k], uy[k] = -eps * sq.y[k];
  const double A = G::area<4>(sq);
  const double div = G::divergence(4, ux, uy, ax, ay, A);
  EXPECT_NEAR(div, -2 * eps, 1e-15);
  const double l = G::characteristic_length<4>(sq, A);
  const double expected = rho * (s / std::sqrt(2.0)) * (2 * eps) * (q2 * C + q1 * (s / std::sqrt(2.0)) * (2 * eps));
  EXPECT_NEAR(bulk_viscosity(rho, l, div, C, q1, q2), expected, 1e-14 * expected);
  // None in expansion.
  EXPECT_EQ(bulk_viscosity(rho, l, -div, C, q1, q2), 0.0);
}

TEST(ForceKernels, EdgeViscosityOnUniformCompression) {
  // A square of side s about the origin compressed uniformly, u = -eps x, limiter off. Each
  // edge has |du| = eps s and the median-surface projection s/2, so its force magnitude is
  // f = rho (c2 g1 eps s + sqrt(c2^2 g1^2 eps^2 s^2 + c1^2 C^2)) s/2 along du; each corner
  // collects (-f eps s) from both of its edges, outward along both axes.
  const double s = 0.4, eps = 1.5, rho = 1.3, C = 0.9, c1 = 0.5, c2 = 1.0, g1 = 0.6;
  const std::vector<double> x = {-s / 2, s / 2, s / 2, -s / 2}, y = {-s / 2, -s / 2, s / 2, s / 2};
  std::vector<double> ux(4), uy(4);
  for (int k = 0; k < 4; ++k) ux[k] = -eps * x[k], uy[k] = -eps * y[k];
  const Index corner_begin[2] = {0, 4}, corner_point[4] = {0, 1, 2, 3};
  const EdgeContinuation continuation[4];
  const double rho_z[1] = {rho}, C_z[1] = {C};
  const EdgeViscosityInput in{corner_begin, corner_point, continuation, x.data(), y.data(), ux.data(),
                              uy.data(),    rho_z,        C_z,          c1,       c2,       false};
  double fx[4] = {0, 0, 0, 0}, fy[4] = {0, 0, 0, 0};
  edge_forces_loop(in, 0, 1, g1, fx, fy);
  const double du = eps * s;
  const double f = rho * (c2 * g1 * du + std::sqrt(c2 * c2 * g1 * g1 * du * du + c1 * c1 * C * C)) * (s / 2);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(fx[k], f * du * (x[k] > 0 ? 1 : -1), 1e-14) << k;
    EXPECT_NEAR(fy[k], f * du * (y[k] > 0 ? 1 : -1), 1e-14) << k;
  }
  // An expanding zone gets nothing.
  for (int k = 0; k < 4; ++k) ux[k] = -ux[k], uy[k] = -uy[k], fx[k] = fy[k] = 0;
  edge_forces_loop(in, 0, 1, g1, fx, fy);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(fx[k], 0.0);
    EXPECT_EQ(fy[k], 0.0);
  }
}

TEST(ForceKernels, HourglassIgnoresRigidAndLinearMotion) {
  const double rho = 1.1, C = 2.3, Q = 0.1;
  auto forces = [&](const ZoneVertices& v, const double* ux, const double* uy, bool fb, double* fx, double* fy) {
    double ax[4], ay[4];
    G::corner_gradients<4>(v, ax, ay);
    for (int k = 0; k < 4; ++k) fx[k] = fy[k] = 0;
    add_hourglass_forces(v.x, v.y, ax, ay, G::area(v), ux, uy, rho, C, Q, fb, fx, fy);
  };
  const double c[2] = {0.7, -0.4};
  const double zero[2][2] = {{0, 0}, {0, 0}}, rotation[2][2] = {{0, -1.3}, {1.3, 0}},
               general[2][2] = {{0.4, -1.3}, {2.1, -0.9}};
  double ux[4], uy[4], fx[4], fy[4];
  // Flanagan-Belytschko: orthogonal to every linear field, on a skewed quad too.
  const ZoneVertices v = skewed_quad();
  for (const auto* L : {&zero, &rotation, &general}) {
    linear_field(v, c, *L, ux, uy);
    forces(v, ux, uy, true, fx, fy);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(fx[k], 0, 1e-14);
      EXPECT_NEAR(fy[k], 0, 1e-14);
    }
  }
  // The gamma mode: a translation always, linear fields on a parallelogram.
  linear_field(v, c, zero, ux, uy);
  forces(v, ux, uy, false, fx, fy);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(fx[k], 0, 1e-15);
    EXPECT_NEAR(fy[k], 0, 1e-15);
  }
  const ZoneVertices par = make({{0, 0}, {2, 0.5}, {2.7, 1.5}, {0.7, 1.0}});
  for (const auto* L : {&rotation, &general}) {
    linear_field(par, c, *L, ux, uy);
    forces(par, ux, uy, false, fx, fy);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(fx[k], 0, 1e-14);
      EXPECT_NEAR(fy[k], 0, 1e-14);
    }
  }
  // The hourglass mode itself, u_x = (1, -1, 1, -1) on a square: g.u = 4, so
  // f_k = -(Q/4 rho C sqrt(A)) g_k 4, opposing the motion; the forces sum to zero.
  const ZoneVertices sq = make({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const double hx[4] = {1, -1, 1, -1}, hy[4] = {0, 0, 0, 0};
  for (bool fb : {false, true}) {
    forces(sq, hx, hy, fb, fx, fy);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(fx[k], -0.25 * Q * rho * C * 1.0 * hx[k] * 4, 1e-15);
      EXPECT_EQ(fy[k], 0.0);
    }
  }
}

TEST(TimeStepKernel, CflAndVolumeLimits) {
  const double cfl = 0.25, q1 = 1.5, q2 = 0.06, fA = 0.1, l = 0.02, C = 3.0;
  // Expansion: the sound crossing time, and the volume limit when it is smaller.
  EXPECT_DOUBLE_EQ(zone_time_step(cfl, q1, q2, fA, l, C, 0.0), cfl * l / C);
  EXPECT_DOUBLE_EQ(zone_time_step(cfl, q1, q2, fA, l, C, 1e4), fA / 1e4);
  // Compression: C replaced by qhat + sqrt(qhat^2 + C^2), qhat = q1 l |div| + q2 C.
  const double div = -20.0, qhat = q1 * l * 20.0 + q2 * C;
  EXPECT_DOUBLE_EQ(zone_time_step(cfl, q1, q2, fA, l, C, div), cfl * l / (qhat + std::sqrt(qhat * qhat + C * C)));
}

TEST(TimeStepKernel, GrowthInitialAndMaximum) {
  // growth 1.1 after the first cycle; dt_init only on the first; dt_max always.
  auto check = [](DtControl c, double dt, DtLimit limit) {
    EXPECT_DOUBLE_EQ(c.dt, dt);
    EXPECT_EQ(c.limit, limit);
  };
  check(control_time_step(1.0, 2.0, false, 1.1, 0, 0), 1.0, DtLimit::cfl);
  check(control_time_step(5.0, 2.0, false, 1.1, 0, 0), 1.1 * 2.0, DtLimit::growth);
  check(control_time_step(5.0, 0.0, true, 1.1, 0.5, 0), 0.5, DtLimit::initial);
  check(control_time_step(5.0, 2.0, false, 1.1, 0.5, 0), 1.1 * 2.0, DtLimit::growth);  // dt_init ignored
  check(control_time_step(5.0, 2.0, false, 1.1, 0, 0.3), 0.3, DtLimit::maximum);
  check(control_time_step(0.2, 2.0, false, 1.1, 0, 0.3), 0.2, DtLimit::cfl);
}

}  // namespace stagger
