#pragma once
// The axisymmetric (r, z) parts of the step (docs/algorithm.md §19): the hoop terms of the
// stress, the point weights that turn area-weighted ("planar") corner forces into true
// ones, and the motion of the massless axis points. Header-only, over explicit inputs.
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/strength.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/mesh.hpp"

namespace stagger {

// Hoop strain rate D_thth = v_r / r of a zone as the part of the volume rate that the area
// rate lacks: (1/V) dV/dt - (1/A) dA/dt, so that tr D = (1/V) dV/dt exactly.
template <int N = 0>
[[gnu::always_inline]] inline double hoop_strain_rate(const ZoneVertices& v, const double* ux, const double* uy,
                                                      const double* ax, const double* ay, double area, double volume) {
  const int n = N ? N : v.n;
  return RzGeometry::volume_divergence<N>(v, ux, uy, volume) - RzGeometry::divergence(n, ux, uy, ax, ay, area);
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

// The corner forces from area-weighted to true: point p's corners are scaled by w_p = M_p /
// m^A_p, M_p its (constant) mass, m^A_p = sum_c rho_z A_c its planar mass on the force
// geometry, so that dv/dt = F_p / M_p is the area-weighted acceleration sum_c f_c / m^A_p.
// The axis points are massless (M_p = 0, w_p = 0): their acceleration is kept in axis_a.
inline void weight_rz_corner_forces(Index np, const Index* point_corner_begin, const Index* point_corners,
                                    const double* corner_area_mass, const double* point_mass, double* fx, double* fy,
                                    double* axis_ax, double* axis_ay) {
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    double mass = 0, Fx = 0, Fy = 0;
    for (Index k = point_corner_begin[p]; k < point_corner_begin[p + 1]; ++k) {
      const Index c = point_corners[k];
      mass += corner_area_mass[c];
      Fx += fx[c];
      Fy += fy[c];
    }
    double w = 0;
    if (point_mass[p] > 0) {
      w = point_mass[p] / mass;
    } else {
      axis_ax[p] = Fx / mass;
      axis_ay[p] = Fy / mass;
    }
    for (Index k = point_corner_begin[p]; k < point_corner_begin[p + 1]; ++k) {
      const Index c = point_corners[k];
      fx[c] *= w;
      fy[c] *= w;
    }
  }
}

// u = v + h a at the axis points (their area-weighted acceleration; F / M is 0 / 0 there).
inline void move_axis_points(std::size_t count, const Index* points, double h, const double* ax, const double* ay,
                             const double* vx, const double* vy, double* ux, double* uy) {
  for (std::size_t i = 0; i < count; ++i) {
    const Index p = points[i];
    ux[p] = vx[p] + h * ax[p];
    uy[p] = vy[p] + h * ay[p];
  }
}

}  // namespace stagger
