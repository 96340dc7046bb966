#pragma once
// Subzonal pressures (Caramana & Shashkov, JCP 142, 1998): docs/algorithm.md §18.
//
// Each zone is split into subzones: its median-mesh corners (corner k: x_k, the midpoints of
// its two edges, and the vertex-average centre), or its side triangles (centre, x_k,
// x_{k+1}). A subzone keeps the mass it had at t = 0, m_k = rho_z^0 V_k^0, so its density
// rho_k = m_k / V_k departs from the zone's when the zone distorts at fixed area (hourglass
// and spurious-vorticity modes, which the zone pressure cannot see). The perturbation
// dp_k = alpha c^2 (rho_k - rho_z) acts on the subzone volumes: the force on vertex j is
// f_j = sum_k dp_k dV_k/dx_j, the exact gradient of the volumes as functions of the zone's
// vertices (the midpoints and the centre being averages of them). Being a gradient of
// volumes that are invariant under rigid motion, the forces sum to zero and do no work under
// translation and rotation; being corner forces, they enter the compatible energy update
// like the zone pressure, so total energy stays exact to round-off. Works for any polygon.
//
// Header-only, over explicit inputs, so that the zone loop inlines it and tests can call it.
#include "hydro/kernels/geometry.hpp"

namespace stagger {

// Corner volumes of the median mesh as sums of half-triangles: with t_k the signed area of
// the triangle (centre, x_k, x_{k+1}), V_k = (t_{k-1} + t_k) / 2. Returns the centre in cx, cy
// and t_k in t; the same decomposition as corner_areas (equal up to round-off).
template <int N = 0>
[[gnu::always_inline]] inline void subzonal_side_triangles(const ZoneVertices& v, double& cx, double& cy, double* t) {
  const int n = N ? N : v.n;
  cx = 0, cy = 0;
  for (int k = 0; k < n; ++k) cx += v.x[k], cy += v.y[k];
  cx /= n;
  cy /= n;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    t[k] = 0.5 * ((v.x[k] - cx) * (v.y[k1] - cy) - (v.x[k1] - cx) * (v.y[k] - cy));
  }
}

// The two subzonings: the paper's median-mesh corners (V_k = (t_{k-1} + t_k) / 2), or the
// side triangles (V_k = t_k, PENNANT's "temporary triangular subzoning").
enum class Subzones { corners, triangles };

// Constant subzonal masses m_k = rho0 V_k at set-up, in the zone's corner order.
template <int N = 0>
inline void subzonal_masses(const ZoneVertices& v, double rho0, Subzones shape, double* mass) {
  const int n = N ? N : v.n;
  double cx, cy, t[kMaxZoneVertices];
  subzonal_side_triangles<N>(v, cx, cy, t);
  for (int k = 0; k < n; ++k)
    mass[k] = rho0 * (shape == Subzones::corners ? 0.5 * (t[k == 0 ? n - 1 : k - 1] + t[k]) : t[k]);
}

// Adds the subzonal-pressure forces of one zone to its corner forces fx[k], fy[k] (k in the
// zone's vertex order). v: the force geometry (the half-step positions in the corrector);
// corner_mass: the zone's constant subzonal masses; zone_mass, area: M_z and the zone area
// on v (rho_z = M_z / A); c2: the zone's squared sound speed (dp/drho); alpha: the merit
// factor. A corner whose volume is not positive (the zone is folding there, which the step
// rejects) gets no perturbation rather than an infinite one.
template <int N = 0>
[[gnu::always_inline]] inline void add_subzonal_pressure_forces(const ZoneVertices& v, const double* subzone_mass,
                                                                double zone_mass, double area, double c2, double alpha,
                                                                Subzones shape, double* fx, double* fy) {
  const int n = N ? N : v.n;
  double cx, cy, t[kMaxZoneVertices], dp[kMaxZoneVertices];
  subzonal_side_triangles<N>(v, cx, cy, t);
  const double rho_z = zone_mass / area, stiffness = alpha * c2;
  const bool corners = shape == Subzones::corners;
  for (int k = 0; k < n; ++k) {
    const double vk = corners ? 0.5 * (t[k == 0 ? n - 1 : k - 1] + t[k]) : t[k];
    dp[k] = vk > 0 ? stiffness * (subzone_mass[k] / vk - rho_z) : 0.0;
  }
  // sum_k dp_k V_k = sum_k pi_k t_k with the side pressure pi_k = (dp_k + dp_{k+1}) / 2 for
  // corners, dp_k for triangles; so f_j = sum_k pi_k dt_k/dx_j, and the centre's share
  // (dt_k/dc) goes 1/n to every vertex.
  double gx = 0, gy = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const double pi = corners ? 0.5 * (dp[k] + dp[k1]) : dp[k];
    if (pi == 0) continue;
    // d(2 t_k)/dx_k = (y_{k+1} - cy, cx - x_{k+1}); d(2 t_k)/dx_{k+1} = (cy - y_k, x_k - cx).
    fx[k] += 0.5 * pi * (v.y[k1] - cy);
    fy[k] += 0.5 * pi * (cx - v.x[k1]);
    fx[k1] += 0.5 * pi * (cy - v.y[k]);
    fy[k1] += 0.5 * pi * (v.x[k] - cx);
    // d(2 t_k)/dc = (y_k - y_{k+1}, x_{k+1} - x_k).
    gx += 0.5 * pi * (v.y[k] - v.y[k1]);
    gy += 0.5 * pi * (v.x[k1] - v.x[k]);
  }
  gx /= n;
  gy /= n;
  for (int k = 0; k < n; ++k) {
    fx[k] += gx;
    fy[k] += gy;
  }
}

}  // namespace stagger
