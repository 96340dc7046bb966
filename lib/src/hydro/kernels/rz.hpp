#pragma once
// The axisymmetric (r, z) parts of the step (docs/algorithm.md §19): the hoop terms of the
// stress, the point weights that turn area-weighted ("planar") corner forces into true
// ones, and the motion of the massless axis points. Header-only, over explicit inputs.
#include "hydro/kernels/compensated.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/strength.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

// Hoop strain rate D_thth = v_r / r of a zone: the mean radial velocity of its vertices over
// their mean radius, sum_k u_k / sum_k x_k (docs/algorithm.md §19.1). For a spherical flow on an
// equal-angle polar mesh it equals the in-plane tangential rate of the planar gradient, so the
// deviator keeps S_thth = S_TT and the hoop force stays radial; exact for v_r = a r. The zone
// is not on the axis (set-up and the tangling check), so sum_k x_k > 0.
template <int N = 0>
[[gnu::always_inline]] inline double hoop_strain_rate(const ZoneVertices& v, const double* ux) {
  const int n = N ? N : v.n;
  double u = 0, r = 0;
  for (int k = 0; k < n; ++k) {
    u += ux[k];
    r += v.x[k];
  }
  return u / r;
}

// The hoop part of the deviatoric rate over a time h: tr D includes D_thth, so S_rr and S_zz
// each lose h 2 mu D_thth / 3 (S_thth = -(S_rr + S_zz) gains 4 mu D_thth h / 3).
[[gnu::always_inline]] inline void add_hoop_stress_rate(double mu, double hoop_rate, double h, Deviator& s) {
  const double d = h * (2.0 / 3.0) * mu * hoop_rate;
  s.xx -= d;
  s.yy -= d;
}

// The hoop body force of the stress on the corners, area-weighted: rho dv_r/dt = ... +
// (sigma_rr - sigma_thth) / r, rho dv_z/dt = ... + sigma_rz / r, with sigma_rr - sigma_thth
// = 2 S_rr + S_zz (the pressure cancels) and r the zone's centroid radius V / A.
[[gnu::always_inline]] inline void add_hoop_forces(int n, const Deviator& s, const double* corner_area, double radius,
                                                   double* fx, double* fy) {
  const double br = (2.0 * s.xx + s.yy) / radius, bz = s.xy / radius;
  for (int k = 0; k < n; ++k) {
    fx[k] += corner_area[k] * br;
    fy[k] += corner_area[k] * bz;
  }
}

// The radius of point p on the force geometry: px[p], or x^n + h v^n when px is null (as Z1).
[[gnu::always_inline]] inline double force_radius(const double* px, const double* x, const double* vx, double h,
                                                  Index p) {
  return px ? px[p] : x[p] + h * vx[p];
}

// The corner forces from area-weighted to true (docs/algorithm.md §19): every corner of point
// p is scaled by its radius r_p on the force geometry, F_c = r_p f^A_c. With the constant point
// mass M_p = r_p^0 m^A_p(0) the acceleration F_p / M_p = sum_c f^A_c / m^A_p(t) is the
// area-weighted one with the planar mass m^A_p(t) = m^A_p(0) r_p^0 / r_p (rho dA = dm / r),
// and the work r_p f^A_c . v_p is p dV exactly on rectangles. The axis points (r_p = 0) get
// no force; their acceleration, kept in axis_a, uses the planar masses of their corners,
// k_c / s_c with s_c the sum of the radii of the corner's two neighbours in its zone
// (their radial stretch; k_c = rho^0 A_c^0 s_c^0), which is what the same corners give at
// the points next to the axis.
inline void weight_rz_forces_loop(Index nc, const Index* corner_point, const double* px, const double* x,
                                  const double* vx, double h, std::size_t axis_count, const Index* axis_points,
                                  const Index* axis_corner_begin, const Index* axis_corner, const Index* axis_ref_a,
                                  const Index* axis_ref_b, const double* axis_moment, double* fx, double* fy,
                                  double* axis_ax, double* axis_ay) {
  for (std::size_t i = 0; i < axis_count; ++i) {
    double mass = 0, Fx = 0, Fy = 0;
    for (Index j = axis_corner_begin[i]; j < axis_corner_begin[i + 1]; ++j) {
      const Index c = axis_corner[j];
      const double s = force_radius(px, x, vx, h, axis_ref_a[j]) + force_radius(px, x, vx, h, axis_ref_b[j]);
      mass += axis_moment[j] / s;
      Fx += fx[c];
      Fy += fy[c];
    }
    axis_ax[axis_points[i]] = Fx / mass;
    axis_ay[axis_points[i]] = Fy / mass;
  }
#pragma omp parallel for schedule(static) if (nc > kParallelMin)
  for (Index c = 0; c < nc; ++c) {
    const double w = force_radius(px, x, vx, h, corner_point[c]);
    fx[c] *= w;
    fy[c] *= w;
  }
}

// u = v + h a at the axis points (their area-weighted acceleration; F / M is 0 / 0 there);
// with low parts (the corrector of a compensated update, docs/algorithm.md §20) v + (h a +
// lo), its round-off the new low part.
inline void move_axis_points(std::size_t count, const Index* points, double h, const double* ax, const double* ay,
                             const double* vx, const double* vy, double* ux, double* uy,
                             const VelocityLowParts& lo = {}) {
  for (std::size_t i = 0; i < count; ++i) {
    const Index p = points[i];
    if (lo.x) {
      ux[p] = two_sum(vx[p], h * ax[p] + lo.x[p], lo.x_new[p]);
      uy[p] = two_sum(vy[p], h * ay[p] + lo.y[p], lo.y_new[p]);
    } else {
      ux[p] = vx[p] + h * ax[p];
      uy[p] = vy[p] + h * ay[p];
    }
  }
}

}  // namespace stagger
