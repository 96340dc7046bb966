// The axisymmetric (rz) kernels (docs/algorithm.md §19): volumes and volume rates against
// closed forms, and the hoop stress of a uniformly expanding ring against the exact elastic
// (and then perfectly plastic) answer.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hydro/kernels/rz.hpp"

namespace stagger {

TEST(Rz, VolumeAndVolumeRateOfARectangle) {
  ZoneVertices v;
  v.n = 4;
  const double xs[4] = {0.5, 2.0, 2.0, 0.5}, ys[4] = {1.0, 1.0, 1.5, 1.5};
  for (int k = 0; k < 4; ++k) v.x[k] = xs[k], v.y[k] = ys[k];
  const double volume = RzGeometry::volume<4>(v);
  EXPECT_NEAR(volume, 0.5 * (4.0 - 0.25) * 0.5, 1e-15);
  // v_r = a r, v_z = b z: dV/dt / V = 2 a + b exactly (V ~ r^2 dz).
  const double a = 0.3, b = -0.7;
  double ux[4], uy[4];
  for (int k = 0; k < 4; ++k) ux[k] = a * v.x[k], uy[k] = b * v.y[k];
  EXPECT_NEAR(RzGeometry::volume_divergence<4>(v, ux, uy, volume), 2 * a + b, 1e-14);
  EXPECT_NEAR(hoop_strain_rate<4>(v, ux), a, 1e-14);
  double cv[4];
  RzGeometry::corner_volumes<4>(v, cv);
  EXPECT_NEAR(cv[0] + cv[1] + cv[2] + cv[3], volume, 1e-15);
}

// A zone of an equal-angle polar mesh (radii R_i, R_o, angles alpha, alpha + d from the axis)
// under a non-uniform radial velocity u_i e_R, u_o e_R: the hoop strain rate equals the
// in-plane tangential rate t . L t of the planar gradient at every angle (docs/algorithm.md
// §19.1), so a spherical deviator keeps S_thth = S_TT. ((1/V) dV/dt - (1/A) dA/dt does not.)
TEST(Rz, HoopStrainRateIsTheTangentialRateOfASphericalFlowOnAnEqualAngleMesh) {
  const double ri = 1.0, ro = 1.3, ui = 0.7, uo = -0.2, d = M_PI / 40;
  for (int j = 0; j < 20; ++j) {
    const double a0 = j * d, a1 = a0 + d, mid = a0 + 0.5 * d;
    const double xs[4] = {ri * std::sin(a1), ro * std::sin(a1), ro * std::sin(a0), ri * std::sin(a0)};
    const double ys[4] = {ri * std::cos(a1), ro * std::cos(a1), ro * std::cos(a0), ri * std::cos(a0)};
    const double us[4] = {ui, uo, uo, ui}, as[4] = {a1, a1, a0, a0};
    ZoneVertices v;
    v.n = 4;
    double ux[4], uy[4], ax[4], ay[4];
    for (int k = 0; k < 4; ++k) {
      v.x[k] = xs[k], v.y[k] = ys[k];
      ux[k] = us[k] * std::sin(as[k]), uy[k] = us[k] * std::cos(as[k]);
    }
    ASSERT_GT(RzGeometry::area<4>(v), 0.0);
    RzGeometry::corner_gradients<4>(v, ax, ay);
    const double area = RzGeometry::area<4>(v);
    const VelocityGradient L = RzGeometry::velocity_gradient(4, ux, uy, ax, ay, area);
    const double tx = std::cos(mid), ty = -std::sin(mid);
    const double tangential = tx * (L.xx * tx + L.xy * ty) + ty * (L.yx * tx + L.yy * ty);
    EXPECT_NEAR(tangential, (ui + uo) / (ri + ro), 1e-14) << "zone " << j;
    EXPECT_NEAR(hoop_strain_rate<4>(v, ux), tangential, 1e-14) << "zone " << j;
  }
}

// A ring zone r in [1, 1.1], z in [0, 0.1] expanding uniformly, v_r = a r, v_z = 0 (the points
// move on the exact path r(t) = r0 e^(a t)): D_rr = D_thth = a, D_zz = 0, so the hypo-elastic
// deviator grows as S_rr = S_thth = 2 mu a t / 3, S_zz = -4 mu a t / 3 (sigma_eq = 2 mu a t)
// until sigma_eq reaches Y, where the radial return holds it.
TEST(Rz, HoopStressOfAUniformlyExpandingRingIsTheExactElasticOne) {
  const double mu = 3.0, a = 0.2, yield = 0.9, dt = 1e-3;
  Deviator s;
  double t = 0, plastic = 0;
  const double r0[4] = {1.0, 1.1, 1.1, 1.0}, z0[4] = {0.0, 0.0, 0.1, 0.1};
  for (int step = 0; step < 1000; ++step) {
    // The half-step geometry and velocity of the zone.
    ZoneVertices v;
    v.n = 4;
    double ux[4], uy[4], ax[4], ay[4];
    for (int k = 0; k < 4; ++k) {
      v.x[k] = r0[k] * std::exp(a * (t + 0.5 * dt));
      v.y[k] = z0[k];
      ux[k] = a * v.x[k];
      uy[k] = 0;
    }
    RzGeometry::corner_gradients<4>(v, ax, ay);
    const double area = RzGeometry::area<4>(v);
    const VelocityGradient L = RzGeometry::velocity_gradient(4, ux, uy, ax, ay, area);
    s = advance_stress(false, mu, s, s, L, dt);
    add_hoop_stress_rate(mu, hoop_strain_rate<4>(v, ux), dt, s);
    plastic += radial_return(yield, 0.0, plastic, mu, s);
    t += dt;
    const double elastic = 2.0 * mu * a * t / 3.0;
    const double thth = -(s.xx + s.yy);
    if (2.0 * mu * a * t <= yield * (1 - 1e-9)) {
      ASSERT_NEAR(thth, elastic, 1e-12 * elastic) << "t = " << t;
      ASSERT_NEAR(s.xx, elastic, 1e-12 * elastic);
      ASSERT_NEAR(s.yy, -2 * elastic, 1e-12 * elastic);
      ASSERT_EQ(plastic, 0.0);
    } else {
      // On the yield surface: the same direction, sigma_eq = Y (S_thth = Y / 3).
      ASSERT_NEAR(thth, yield / 3.0, 1e-12) << "t = " << t;
      ASSERT_NEAR(s.yy, -2 * yield / 3.0, 1e-12);
    }
  }
  EXPECT_GT(plastic, 0.0);  // the run went past first yield (2 mu a t = Y at t = 0.75)
}

// The radius weight of docs/algorithm.md §19: sum_k x_k a_k . u_k, the work rate per unit
// pressure of the weighted planar forces, is the exact volume rate dV/dt of a rectangle moved
// as a rectangle (edges with their own normal speeds), the axis included.
TEST(Rz, RadiusWeightedWorkIsTheVolumeRateOfARectangle) {
  for (const double x0 : {0.0, 0.5}) {
    ZoneVertices v;
    v.n = 4;
    const double xs[4] = {x0, 2.0, 2.0, x0}, ys[4] = {1.0, 1.0, 1.5, 1.5};
    for (int k = 0; k < 4; ++k) v.x[k] = xs[k], v.y[k] = ys[k];
    const double left = x0 > 0 ? -0.4 : 0.0, right = 0.7, bottom = -0.2, top = 0.9;
    const double ux[4] = {left, right, right, left}, uy[4] = {bottom, bottom, top, top};
    double ax[4], ay[4];
    RzGeometry::corner_gradients<4>(v, ax, ay);
    double work = 0;
    for (int k = 0; k < 4; ++k) work += v.x[k] * (ax[k] * ux[k] + ay[k] * uy[k]);
    const double volume = RzGeometry::volume<4>(v);
    EXPECT_NEAR(work, RzGeometry::volume_divergence<4>(v, ux, uy, volume) * volume, 1e-14) << "x0 = " << x0;
  }
}

// Boundary tractions per radian: the planar point forces times the point's radius, zero on the
// axis; planar: as they are.
TEST(Rz, SurfaceForcesAreScaledByTheRadius) {
  const std::vector<double> x = {0.0, 0.5, 2.0};
  std::vector<double> fx = {1.0, -2.0, 3.0}, fy = {4.0, 5.0, -6.0};
  PlanarGeometry::scale_surface_forces(x, fx, fy);
  EXPECT_EQ(fx, (std::vector<double>{1.0, -2.0, 3.0}));
  RzGeometry::scale_surface_forces(x, fx, fy);
  EXPECT_EQ(fx, (std::vector<double>{0.0, -1.0, 6.0}));
  EXPECT_EQ(fy, (std::vector<double>{0.0, 2.5, -12.0}));
}

}  // namespace stagger
