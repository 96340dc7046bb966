#pragma once
// The point loops of the step (docs/algorithm.md §1): P1 (steps 2 and 4) and P2 (step 6),
// the commit of the positions, and the work of the boundary and external forces. Each point
// gathers its corners' forces in a fixed order (corner_forces.hpp).
#include "hydro/exact_sum.hpp"
#include "hydro/kernels/compensated.hpp"
#include "hydro/kernels/corner_forces.hpp"
#include "hydro/kernels/zone_status.hpp"

namespace stagger {

// Read-only inputs of the point loops.
struct PointInput {
  const Index *point_corner_begin, *point_corners;
  const double *fx, *fy;  // corner forces (f^{n-1/2} in P1, f^{n+1/2} in P2)
  const double* mass;     // M_p
  const double *x, *y, *vx, *vy;
};

// P1: x^{n+1/2} = x^n + h v^n (when x_half is given) and v* = v^n + h F / M_p, h = dt/2.
inline void predict_velocity_loop(const PointInput& in, Index np, double h, double* x_half, double* y_half,
                                  double* vx_star, double* vy_star) {
  const double *x = in.x, *y = in.y, *vx = in.vx, *vy = in.vy, *M = in.mass;
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    double Fx, Fy;
    gather_point_sum(in.point_corner_begin, in.point_corners, in.fx, in.fy, p, Fx, Fy);
    if (x_half) {
      x_half[p] = x[p] + h * vx[p];
      y_half[p] = y[p] + h * vy[p];
    }
    vx_star[p] = vx[p] + h * Fx / M[p];
    vy_star[p] = vy[p] + h * Fy / M[p];
  }
}

// v += h (F_ext + F_src) / M_p: applied pressures and momentum sources (src may be null).
inline void add_external_velocity(Index np, double h, const double* mass, const double* ext_fx, const double* ext_fy,
                                  const double* src_fx, const double* src_fy, double* vx, double* vy) {
  const bool sources = src_fx != nullptr;
  for (Index p = 0; p < np; ++p) {
    vx[p] += h * (ext_fx[p] + (sources ? src_fx[p] : 0.0)) / mass[p];
    vy[p] += h * (ext_fy[p] + (sources ? src_fy[p] : 0.0)) / mass[p];
  }
}

// P2: v_free = v^n + dt (F + F_ext + F_src) / M_p (ext and src may be null); compensated, v^n
// + (dt F / M_p + lo) with its round-off as the new low part.
inline void correct_velocity_loop(const PointInput& in, Index np, double dt, const double* ext_fx, const double* ext_fy,
                                  const double* src_fx, const double* src_fy, const VelocityLowParts& lo,
                                  double* vx_new, double* vy_new) {
  const double *vx = in.vx, *vy = in.vy, *M = in.mass;
  const bool external = ext_fx != nullptr, sources = src_fx != nullptr;
  const auto force = [&](Index p, double& Fx, double& Fy) {
    gather_point_sum(in.point_corner_begin, in.point_corners, in.fx, in.fy, p, Fx, Fy);
    if (external) {
      Fx += ext_fx[p] + (sources ? src_fx[p] : 0.0);
      Fy += ext_fy[p] + (sources ? src_fy[p] : 0.0);
    }
  };
  if (lo.x) {  // one loop per variant: no test per point
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      double Fx, Fy;
      force(p, Fx, Fy);
      vx_new[p] = two_sum(vx[p], dt * Fx / M[p] + lo.x[p], lo.x_new[p]);
      vy_new[p] = two_sum(vy[p], dt * Fy / M[p] + lo.y[p], lo.y_new[p]);
    }
    return;
  }
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    double Fx, Fy;
    force(p, Fx, Fy);
    vx_new[p] = vx[p] + dt * Fx / M[p];
    vy_new[p] = vy[p] + dt * Fy / M[p];
  }
}

// x^{n+1} = x^n + dt v_bar, v_bar = (v^n + v^{n+1})/2: the expression Z2 used for the end
// geometry, so the committed positions are the ones checked. With low parts (x_lo, y_lo not
// null; docs/algorithm.md §20) the same rounded sum x^n + (dt v_bar + lo), whose round-off
// becomes the new low part.
inline void commit_loop(Index np, double dt, const double* vx, const double* vy, const double* ux, const double* uy,
                        double* x, double* y, double* x_lo, double* y_lo) {
  if (x_lo) {
#pragma omp parallel for schedule(static) if (np > kParallelMin)
    for (Index p = 0; p < np; ++p) {
      x[p] = two_sum(x[p], dt * 0.5 * (vx[p] + ux[p]) + x_lo[p], x_lo[p]);
      y[p] = two_sum(y[p], dt * 0.5 * (vy[p] + uy[p]) + y_lo[p], y_lo[p]);
    }
    return;
  }
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    x[p] = x[p] + dt * 0.5 * (vx[p] + ux[p]);
    y[p] = y[p] + dt * 0.5 * (vy[p] + uy[p]);
  }
}

// Work of the velocity constraints: sum over the constrained points of M_p (v^{n+1} - v_free)
// . v_bar (the momentum they added, times the same v_bar as the zones' energy update).
// (Exact sums, skipping the points flagged in `skip` (a distributed run's ghosts; may be null).)
inline void constraint_work(std::size_t count, const Index* points, const unsigned char* skip, const double* mass,
                            const double* vx, const double* vy, const double* ux, const double* uy,
                            const double* free_vx, const double* free_vy, ExactSum& work) {
  for (std::size_t i = 0; i < count; ++i) {
    const Index p = points[i];
    if (skip && skip[p]) continue;
    const double bx = 0.5 * (vx[p] + ux[p]), by = 0.5 * (vy[p] + uy[p]);
    work.add(mass[p] * ((ux[p] - free_vx[i]) * bx + (uy[p] - free_vy[i]) * by));
  }
}

// Work over dt of the applied-pressure forces and of the momentum sources (src may be null)
// with v_bar: dt sum_p F_p . v_bar_p, added to external_work and source_work.
inline void point_force_work(Index np, const unsigned char* skip, double dt, const double* vx, const double* vy,
                             const double* ux, const double* uy, const double* ext_fx, const double* ext_fy,
                             const double* src_fx, const double* src_fy, ExactSum& external_work,
                             ExactSum& source_work) {
  for (Index p = 0; p < np; ++p) {
    if (skip && skip[p]) continue;
    const double bx = 0.5 * (vx[p] + ux[p]), by = 0.5 * (vy[p] + uy[p]);
    external_work.add(dt * (ext_fx[p] * bx + ext_fy[p] * by));
    if (src_fx) source_work.add(dt * (src_fx[p] * bx + src_fy[p] * by));
  }
}

}  // namespace stagger
