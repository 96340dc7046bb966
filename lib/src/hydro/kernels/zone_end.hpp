#pragma once
// Loop Z2 of the step (docs/algorithm.md §1, steps 7, 8 and 9): per zone, the energy and
// stress at t^{n+1}, the end geometry, density, EOS and time-step candidate. One fused loop
// calling the kernels, over explicit inputs and outputs.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "eos/eos_kernels.hpp"
#include "hydro/kernels/burn.hpp"
#include "hydro/kernels/compensated.hpp"
#include "hydro/kernels/energy.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/rz.hpp"
#include "hydro/kernels/strength.hpp"
#include "hydro/kernels/time_step.hpp"
#include "hydro/kernels/zone_model.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "hydro/kernels/zone_validity.hpp"
#include "stagger/problem.hpp"

namespace stagger {

// The mass measure of a zone: its area, or in rz its volume per radian.
template <int N, class Geometry>
[[gnu::always_inline]] inline double zone_measure(const ZoneVertices& v) {
  if constexpr (Geometry::kRz) {
    return Geometry::template volume<N>(v);
  } else {
    return Geometry::template area<N>(v);
  }
}

// Outputs of the end-of-step state of a zone (per zone arrays; grad_* only with strength).
struct ZoneStateOutput {
  double *area, *rho, *p, *c;
  double *grad_xx, *grad_xy, *grad_yx, *grad_yy;  // L(v^{n+1}) on x^{n+1}
};

// Step 9 for zone z: end geometry (zone area > 0, no crossing edges, corner areas > 0 if
// checked), density, EOS (p times the burn fraction), full sound speed, L(u) on the end geometry (strength) and
// the time-step candidate dt_zone from div u. Shared with the state recomputation (set-up,
// restart, remap, failed step) so that a restart reproduces it bitwise. Returns the failure
// code or kNoFailure; writes nothing of the state on failure before the EOS. kPlain: the
// material has neither strength nor burn (m's flags are then not read).
template <int N, class Geometry, bool kPlain = false, class Eos>
[[gnu::always_inline]] inline std::int64_t end_state(Index z, const ZoneVertices& v, const double* ux, const double* uy,
                                                     double mass, double energy, double burn, const HydroOptions& o,
                                                     const Eos& eos, const ZoneModel& m, const ZoneStateOutput& out,
                                                     double& dt_zone) {
  double ca[kMaxZoneVertices], ax[kMaxZoneVertices], ay[kMaxZoneVertices];
  const bool strength = !kPlain && m.strength, burning = !kPlain && m.burn;
  const double area = Geometry::template area<N>(v);
  // Always: a non-positive area or crossing edges (docs/algorithm.md §9); optionally also a
  // folded median-mesh corner.
  if (!(area > 0) || edges_cross<N>(v) || (o.check_corner_areas && !(Geometry::template corner_areas<N>(v, ca) > 0)))
    return failure_code(z, kTangled);
  // The mass measure: the area, or in rz the volume per radian (docs/algorithm.md §19).
  double measure = area;
  if constexpr (Geometry::kRz) {
    measure = Geometry::template volume<N>(v);
    bool across = !(measure > 0);
    for (int k = 0; k < (N ? N : v.n); ++k) across = across || v.x[k] < 0;
    if (across) return failure_code(z, kTangled);
  }
  const double rho = mass / measure;
  eos::PressureSound ps{};
  if (!eos::evaluate(eos, rho, energy, ps) || energy < m.min_energy) return failure_code(z, kEosDomain);
  const double C = full_sound_speed(ps.c2, rho, strength, m.mu);
  out.area[z] = measure;
  out.rho[z] = rho;
  out.p[z] = burning ? burn * ps.p : ps.p;
  out.c[z] = C;
  if (!std::isfinite(out.p[z]) || !std::isfinite(C)) return failure_code(z, kNotFinite);
  const int n = N ? N : v.n;
  Geometry::template corner_gradients<N>(v, ax, ay);
  double div;
  if constexpr (Geometry::kRz) {
    div = Geometry::template volume_divergence<N>(v, ux, uy, measure);
  } else {
    div = Geometry::divergence(n, ux, uy, ax, ay, area);
  }
  if (strength) {
    // The next step's predictor needs L(v^n) on x^n: this is it.
    const VelocityGradient L = Geometry::velocity_gradient(n, ux, uy, ax, ay, area);
    out.grad_xx[z] = L.xx, out.grad_xy[z] = L.xy, out.grad_yx[z] = L.yx, out.grad_yy[z] = L.yy;
  }
  dt_zone =
      zone_time_step(o.cfl, o.q1, o.q2, o.volume_limit, Geometry::template characteristic_length<N>(v, area), C, div);
  return kNoFailure;
}

// Read-only inputs of Z2.
struct ZoneEndInput {
  const Index* zone_corner_begin;
  const Index* corner_point;
  const double *x, *y;            // x^n
  const double *x_lo, *y_lo;      // their low parts (compensated update, docs/algorithm.md §20; else null)
  const double *x_half, *y_half;  // x^{n+1/2} (stored when strength or an energy source need it)
  const double *vx, *vy;          // v^n
  const double *ux, *uy;          // v^{n+1}
  const double *fx, *fy;          // f^{n+1/2} per corner
  const double *zone_mass, *e;
  const double *sxx, *syy, *sxy, *sxx_half, *syy_half, *sxy_half, *plastic;  // (strength)
  const double *burn, *lighting_time, *burn_length;                          // (burn)
  const EnergySource* energy_source;                                         // null: none
  double dt, t_new;
  const double* heat_rate;  // heat flux energy rate per zone at t^n (docs/algorithm.md §21); null: off
};

// Outputs of Z2 (null where absent).
struct ZoneEndOutput {
  double* e_new;
  double* source_energy;  // M_z dt s_e per zone (energy source)
  double *sxx_new, *syy_new, *sxy_new, *plastic_new;
  double* burn_new;
  ZoneStateOutput state;
};

// Z2 needs none of strength, burn, energy source, heat flux or the positions' low parts:
// end_of_step_loop<N, G, true> then gives the same bits without testing for them per zone.
inline bool plain_zone_end(const ZoneEndInput& in, const ZoneModel& m) {
  return !m.strength && !m.burn && !in.energy_source && !in.heat_rate && !in.x_lo;
}

// Z2 over the zones [begin, end) of one material. Merges the zones' dt candidates into
// `choice`; returns the lowest zone's failure code, kNoFailure if none. kPlain: plain_zone_end
// holds, and the tests for what it excludes are compiled out.
template <int N, class Geometry, bool kPlain = false, class Eos>
std::int64_t end_of_step_loop(const ZoneEndInput& input, const HydroOptions& o, const ZoneModel& m, const Eos& eos,
                              Index begin, Index end, const ZoneEndOutput& output, DtChoice& choice) {
  std::int64_t failure = kNoFailure;
  DtChoice best;
#pragma omp parallel if (end - begin > kParallelMin)
  {
    // Thread-private copies, as in zone_forces_loop, and the loop's pointers and flags taken from
    // them inside the region: they stay in registers or the thread's frame.
    const ZoneEndInput in = input;
    const ZoneEndOutput out = output;
    const Index* cb = in.zone_corner_begin;
    const Index* cp = in.corner_point;
    const double *vx = in.vx, *vy = in.vy, *ux = in.ux, *uy = in.uy, *x = in.x, *y = in.y;
    const double *x_lo = kPlain ? nullptr : in.x_lo, *y_lo = kPlain ? nullptr : in.y_lo;
    const bool strength = !kPlain && m.strength, burning = !kPlain && m.burn;
    const bool energy_source = !kPlain && in.energy_source, heat_flux = !kPlain && in.heat_rate;
    const double dt = in.dt;
    const bool objective = o.stress_update == StressUpdate::objective;
    DtChoice local;
#pragma omp for schedule(static) reduction(min : failure) nowait
    for (Index z = begin; z < end; ++z) {
      const Index b = cb[z];
      const int n = N ? N : cb[z + 1] - b;
      double bx[kMaxZoneVertices], by[kMaxZoneVertices], nx[kMaxZoneVertices], ny[kMaxZoneVertices];
      for (int k = 0; k < n; ++k) {
        const Index p = cp[b + k];
        nx[k] = ux[p];
        ny[k] = uy[p];
        bx[k] = 0.5 * (vx[p] + nx[k]);
        by[k] = 0.5 * (vy[p] + ny[k]);
      }
      // Step 9's end geometry x^{n+1} = x^n + dt v_bar, formed here (committed after the whole
      // step succeeds) before the loop's first store, which the compiler must assume could
      // change x, v or u: read once, not again after the store.
      ZoneVertices ve;
      ve.n = n;
      if (x_lo) {  // compensated (§20): the low parts join the step
        for (int k = 0; k < n; ++k) {
          const Index p = cp[b + k];
          ve.x[k] = x[p] + (dt * 0.5 * (vx[p] + ux[p]) + x_lo[p]);
          ve.y[k] = y[p] + (dt * 0.5 * (vy[p] + uy[p]) + y_lo[p]);
        }
      } else {
        for (int k = 0; k < n; ++k) {
          const Index p = cp[b + k];
          ve.x[k] = x[p] + dt * 0.5 * (vx[p] + ux[p]);
          ve.y[k] = y[p] + dt * 0.5 * (vy[p] + uy[p]);
        }
      }
      // Step 7: M_z (e^{n+1} - e^n) = -dt sum_c f_c . v_bar.
      const double mass = in.zone_mass[z];
      double energy = energy_after_work(in.e[z], dt, corner_work(n, in.fx + b, in.fy + b, bx, by), mass);
      if (energy_source) {
        const ZoneVertices vh = gather_vertices<N>(cp, b, n, in.x_half, in.y_half);
        const auto [cx, cy] = Geometry::template centre<N>(vh);
        const double se = (*in.energy_source)(cx, cy, in.t_new - 0.5 * dt);
        energy += dt * se;
        out.source_energy[z] = dt * se * mass;
      }
      // The heat flux: internal energy exchanged with the neighbours, conservative (§21).
      if (heat_flux) energy += dt * in.heat_rate[z] / mass;
      out.e_new[z] = energy;
      // Step 8: S^{n+1} = return(S^n + dt dS/dt(S^{n+1/2}, L(v_bar) on the half geometry)).
      if (strength) {
        const ZoneVertices vh = gather_vertices<N>(cp, b, n, in.x_half, in.y_half);
        double ax[kMaxZoneVertices], ay[kMaxZoneVertices];
        Geometry::template corner_gradients<N>(vh, ax, ay);
        const double area_h = Geometry::template area<N>(vh);
        const VelocityGradient L = Geometry::velocity_gradient(n, bx, by, ax, ay, area_h);
        Deviator sn = advance_stress(objective, m.mu, {in.sxx[z], in.syy[z], in.sxy[z]},
                                     {in.sxx_half[z], in.syy_half[z], in.sxy_half[z]}, L, dt);
        if constexpr (Geometry::kRz) add_hoop_stress_rate(m.mu, hoop_strain_rate<N>(vh, bx), dt, sn);
        out.plastic_new[z] = in.plastic[z] + radial_return(m.yield, m.hardening, in.plastic[z], m.mu, sn);
        out.sxx_new[z] = sn.xx, out.syy_new[z] = sn.yy, out.sxy_new[z] = sn.xy;
      }
      // Step 9: density, EOS and time-step candidate on the end geometry.
      double burn = 1;
      if (burning) {
        burn = burn_fraction(in.burn[z], in.t_new, in.lighting_time[z], in.burn_length[z], m.burn_model,
                             mass / zone_measure<N, Geometry>(ve));
        out.burn_new[z] = burn;
      }
      double dtz = 1e300;
      std::int64_t code = end_state<N, Geometry, kPlain>(z, ve, nx, ny, mass, energy, burn, o, eos, m, out.state, dtz);
      if (code == kNoFailure && !std::isfinite(energy)) code = failure_code(z, kNotFinite);
      failure = std::min(failure, code);
      if (dtz < local.dt) local = {dtz, z};
    }
#pragma omp critical
    merge_thread_choice(best, local);
  }
  merge_range_choice(choice, best);
  return failure;
}

}  // namespace stagger
