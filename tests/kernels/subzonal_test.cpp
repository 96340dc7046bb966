// Subzonal pressures (docs/algorithm.md §18): the corner forces of one zone are the exact
// gradient of sum_k dp_k V_k, conserve momentum, do no work under rigid motion, vanish under
// any affine deformation of the zone, resist the hourglass mode. Runs with them:
// tests/step/subzonal_run_test.cpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hydro/kernels/subzonal_pressure.hpp"

namespace stagger {

namespace {

// A star-shaped polygon with n vertices on a wobbly circle (counter-clockwise).
ZoneVertices wobbly_polygon(int n, double wobble) {
  ZoneVertices v;
  v.n = n;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n + 0.1 * std::sin(3.0 * k);
    const double r = 1.0 + wobble * std::cos(5.0 * k + 1);
    v.x[k] = 0.3 + r * std::cos(a);
    v.y[k] = -0.2 + 0.8 * r * std::sin(a);
  }
  return v;
}

struct Forces {
  double fx[kMaxZoneVertices] = {}, fy[kMaxZoneVertices] = {};
  double scale = 0;  // sum |f|
};

Forces forces(const ZoneVertices& v, const double* mass, Subzones shape, double c2 = 2.0, double alpha = 0.7) {
  double zone_mass = 0;
  for (int k = 0; k < v.n; ++k) zone_mass += mass[k];
  Forces f;
  add_subzonal_pressure_forces(v, mass, zone_mass, PlanarGeometry::area(v), c2, alpha, shape, f.fx, f.fy);
  for (int k = 0; k < v.n; ++k) f.scale += std::hypot(f.fx[k], f.fy[k]);
  return f;
}

// Masses of a distorted initial zone: subzonal densities differ from the zone's now.
std::vector<double> masses_of(const ZoneVertices& v0, double rho0, Subzones shape) {
  std::vector<double> m(v0.n);
  subzonal_masses(v0, rho0, shape, m.data());
  return m;
}

// Subzone volume k from the side triangles t.
double subzone_volume(const double* t, int k, int n, Subzones shape) {
  return shape == Subzones::corners ? 0.5 * (t[(k + n - 1) % n] + t[k]) : t[k];
}

constexpr Subzones kShapes[] = {Subzones::corners, Subzones::triangles};

}  // namespace

TEST(Subzonal, ForcesAreTheGradientOfTheSubzonalPressureWork) {
  // With dp_k frozen, f_j = d/dx_j sum_k dp_k V_k: compare with central differences.
  for (Subzones shape : kShapes)
    for (int n : {4, 5, 6, 8}) {
      const ZoneVertices v = wobbly_polygon(n, 0.15);
      const std::vector<double> m = masses_of(wobbly_polygon(n, 0.0), 1.3, shape);
      const Forces f = forces(v, m.data(), shape, 1.0, 1.0);
      ASSERT_GT(f.scale, 1e-3) << n;
      double zone_mass = 0;
      for (double mk : m) zone_mass += mk;
      double cx, cy, t[kMaxZoneVertices], dp[kMaxZoneVertices];
      subzonal_side_triangles(v, cx, cy, t);
      for (int k = 0; k < n; ++k) dp[k] = m[k] / subzone_volume(t, k, n, shape) - zone_mass / PlanarGeometry::area(v);
      auto work = [&](const ZoneVertices& w) {
        double c_x, c_y, tw[kMaxZoneVertices], sum = 0;
        subzonal_side_triangles(w, c_x, c_y, tw);
        for (int k = 0; k < n; ++k) sum += dp[k] * subzone_volume(tw, k, n, shape);
        return sum;
      };
      const double h = 1e-6;
      for (int j = 0; j < n; ++j) {
        ZoneVertices a = v, b = v;
        a.x[j] += h, b.x[j] -= h;
        EXPECT_NEAR(f.fx[j], (work(a) - work(b)) / (2 * h), 1e-8) << n << " " << j;
        a = v, b = v;
        a.y[j] += h, b.y[j] -= h;
        EXPECT_NEAR(f.fy[j], (work(a) - work(b)) / (2 * h), 1e-8) << n << " " << j;
      }
    }
}

TEST(Subzonal, ForcesSumToZeroAndDoNoWorkUnderRigidMotion) {
  for (Subzones shape : kShapes)
    for (int n : {4, 5, 6, 7, 8}) {
      const ZoneVertices v = wobbly_polygon(n, 0.2);
      const std::vector<double> m = masses_of(wobbly_polygon(n, 0.05), 2.0, shape);
      const Forces f = forces(v, m.data(), shape);
      ASSERT_GT(f.scale, 1e-2) << n;
      double sx = 0, sy = 0, rotation_work = 0, rotation_scale = 0;
      for (int k = 0; k < n; ++k) {
        sx += f.fx[k], sy += f.fy[k];
        // Rigid rotation about an arbitrary point: u = omega x (x - x0).
        const double ux = -(v.y[k] - 0.7), uy = v.x[k] + 0.4;
        rotation_work += f.fx[k] * ux + f.fy[k] * uy;
        rotation_scale += std::hypot(f.fx[k], f.fy[k]) * std::hypot(ux, uy);
      }
      EXPECT_LT(std::abs(sx), 1e-14 * f.scale) << n;  // momentum; translation does no work
      EXPECT_LT(std::abs(sy), 1e-14 * f.scale) << n;
      EXPECT_LT(std::abs(rotation_work), 1e-14 * rotation_scale) << n;
    }
}

TEST(Subzonal, NoForceUnderUniformCompressionOrAnyAffineDeformation) {
  // The median mesh is affine-covariant, so all corner volumes scale by det(A) and the
  // subzonal densities stay equal to the zone's: a uniform compression, a shear, a
  // stretch of a distorted zone give no subzonal force (unlike the Gamma hourglass force).
  // Any triangle is an affine image of any other: triangles never get a subzonal force.
  for (Subzones shape : kShapes)
    for (int n : {3, 4, 5, 6, 8}) {
      const ZoneVertices v0 = wobbly_polygon(n, 0.2);
      const std::vector<double> m = masses_of(v0, 1.7, shape);
      const double maps[3][4] = {{0.5, 0, 0, 0.5}, {1.0, 0.6, 0, 1.0}, {1.3, 0.2, -0.4, 0.45}};
      for (const auto& a : maps) {
        ZoneVertices v = v0;
        for (int k = 0; k < n; ++k) {
          v.x[k] = a[0] * v0.x[k] + a[1] * v0.y[k] + 0.25;
          v.y[k] = a[2] * v0.x[k] + a[3] * v0.y[k] - 1.5;
        }
        const Forces f = forces(v, m.data(), shape, 2.0, 1.0);
        // Scale of a real pressure force here: c^2 rho times the zone size ~ 2 * 1.7 * 1.
        EXPECT_LT(f.scale, 1e-13) << n;
      }
    }
}

TEST(Subzonal, TheHourglassModeMeetsARestoringForce) {
  // A square and a regular hexagon pushed along their alternating (hourglass) mode: the
  // force opposes the displacement, so the work done on the mode is negative, and it grows
  // linearly with the amplitude.
  for (Subzones shape : kShapes)
    for (int n : {4, 6}) {
      ZoneVertices v0;
      v0.n = n;
      for (int k = 0; k < n; ++k) v0.x[k] = std::cos(2 * M_PI * k / n), v0.y[k] = std::sin(2 * M_PI * k / n);
      const std::vector<double> m = masses_of(v0, 1.0, shape);
      double previous = 0;
      for (double eps : {1e-3, 2e-3}) {
        for (const auto& dir : {std::array<double, 2>{1, 0}, std::array<double, 2>{0.6, 0.8}}) {
          ZoneVertices v = v0;
          for (int k = 0; k < n; ++k) {
            const double g = (k % 2) ? -1.0 : 1.0;
            v.x[k] += eps * g * dir[0];
            v.y[k] += eps * g * dir[1];
          }
          const Forces f = forces(v, m.data(), shape, 1.0, 1.0);
          double along = 0;  // force projected on the mode: d(work)/d(eps)
          for (int k = 0; k < n; ++k) along += ((k % 2) ? -1.0 : 1.0) * (f.fx[k] * dir[0] + f.fy[k] * dir[1]);
          EXPECT_LT(along, 0) << n << " eps " << eps;
          if (dir[0] == 1) {
            if (previous != 0) {
              EXPECT_NEAR(along / previous, 2.0, 0.02) << n;
            }
            previous = along;
          }
        }
      }
    }
}

}  // namespace stagger
