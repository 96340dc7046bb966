// The compatible staggered Lagrangian step (docs/algorithm.md §1). try_step below is the
// numbered table of that section, one call per row; the physics is in the kernels of
// hydro/kernels/ (explicit inputs and outputs, no access to the whole state). The calls here
// bind the state's arrays to them. Loops are fused per entity:
//   P1 points: predictor gather, half positions, v*                (steps 2, 4)
//   Z1 zones : half geometry, half state, q, hourglass, f_c        (steps 2, 3, 5)
//   P2 points: corrector gather, v^{n+1}, constraints              (step 6)
//   Z2 zones : energy, stress, end geometry, EOS, dt               (steps 7, 8, 9)
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "hydro/boundary.hpp"
#include "hydro/collective.hpp"
#include "hydro/diagnostics.hpp"
#include "hydro/exact_sum.hpp"
#include "hydro/kernels/compensated.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/heat_flux.hpp"
#include "hydro/kernels/points.hpp"
#include "hydro/kernels/rz.hpp"
#include "hydro/kernels/viscosity_edge.hpp"
#include "hydro/kernels/zone_end.hpp"
#include "hydro/kernels/zone_forces.hpp"
#include "hydro/kernels/zone_validity.hpp"
#include "hydro/simulation_impl.hpp"
#include "stagger/error.hpp"
#include "state/state_table.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

namespace {

// The kernels' geometry policy (docs/architecture.md, "Geometry policy"): planar, or rz
// (docs/algorithm.md §19), chosen once per loop; f gets a value of the policy type.
using Geometry = PlanarGeometry;  // the geometry of diagnostics (tangled-zone search)
template <class F>
decltype(auto) with_geometry(bool rz, F&& f) {
  return rz ? f(RzGeometry{}) : f(PlanarGeometry{});
}

// The per-material constants of the zone kernels.
ZoneModel zone_model(const Material& material) {
  ZoneModel m;
  m.min_energy = material.min_energy;
  if (material.strength) {
    m.strength = true;
    const LinearHardening constants = zone_loop_constants(*material.strength);  // one visit per range
    m.mu = constants.shear_modulus;
    m.yield = constants.yield_stress;
    m.hardening = constants.hardening_modulus;
  }
  if (material.burn) {
    m.burn = true;
    m.burn_model.detonation_speed = material.burn->detonation_speed;
    m.burn_model.beta_burn = material.burn->beta_burn;
    m.burn_model.cj_relative_volume = material.burn->cj_relative_volume;
    m.burn_model.rho0 = std::get<Jwl>(material.eos).rho0;
  }
  // (gamma+1)/4 of the edge viscosity's quadratic term; its analogue s/2 for Mie-Gruneisen.
  if (const auto* g = std::get_if<IdealGas>(&material.eos)) m.edge_gamma_factor = (g->gamma + 1) / 4;
  if (const auto* mg = std::get_if<MieGruneisen>(&material.eos)) m.edge_gamma_factor = mg->s / 2;
  if (const auto* j = std::get_if<Jwl>(&material.eos)) m.edge_gamma_factor = (j->omega + 2) / 4;
  if (const auto* sg = std::get_if<StiffenedGas>(&material.eos)) m.edge_gamma_factor = (sg->gamma + 1) / 4;
  return m;
}

// Calls f(range, eos, model) for each range of zones (one material each) with its EOS type.
template <class F>
void for_each_range(const Simulation::Impl& s, F&& f) {
  for (const ZoneRange& r : s.ranges) {
    const Material& material = s.problem.materials[r.material];
    const ZoneModel m = zone_model(material);
    std::visit([&](const auto& eos) { f(r, eos, m); }, material.eos);
  }
}

const EnergySource* energy_source(const Simulation::Impl& s) {
  return s.problem.sources && s.problem.sources->energy ? &s.problem.sources->energy : nullptr;
}

template <class T>
T* data_or_null(std::vector<T>& v) {
  return v.empty() ? nullptr : v.data();
}

ZoneStateOutput state_output(Simulation::Impl& s) {
  return {.area = s.area.data(),
          .rho = s.rho.data(),
          .p = s.p.data(),
          .c = s.c.data(),
          .grad_xx = s.grad_xx.data(),
          .grad_xy = s.grad_xy.data(),
          .grad_yx = s.grad_yx.data(),
          .grad_yy = s.grad_yy.data()};
}

PointInput point_input(const Simulation::Impl& s) {
  return {.point_corner_begin = s.point_corner_begin.data(),
          .point_corners = s.point_corners.data(),
          .fx = s.corner_fx.data(),
          .fy = s.corner_fy.data(),
          .mass = s.point_mass.data(),
          .x = s.x.data(),
          .y = s.y.data(),
          .vx = s.vx.data(),
          .vy = s.vy.data()};
}

}  // namespace

namespace {
// Distributed runs: the lowest failure and the smallest dt over the ranks (serial: as is).
std::int64_t agreed(const Simulation::Impl& s, std::int64_t failure) {
  return s.collective ? s.collective->min_failure(s, failure) : failure;
}
DtChoice agreed(const Simulation::Impl& s, DtChoice choice) {
  return s.collective ? s.collective->min_dt(s, choice) : choice;
}
}  // namespace

void Simulation::Impl::recompute_state() {
  wall_clearance.valid = false;  // the points moved (restore, remap) or went back (retry)
  DtChoice best;
  std::int64_t failure = kNoFailure;
  const bool quads = all_quads;
  const HydroOptions& o = problem.options;
  const ZoneStateOutput out = state_output(*this);
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const ZoneModel& m) {
    DtChoice range_best;
#pragma omp parallel if (r.end - r.begin > kParallelMin)
    {
      DtChoice local;
#pragma omp for schedule(static) reduction(min : failure) nowait
      for (Index z = r.begin; z < r.end; ++z) {
        const Index b = zone_corner_begin[z];
        const int n = zone_corner_begin[z + 1] - b;
        const ZoneVertices v = gather_vertices<0>(corner_point.data(), b, n, x.data(), y.data());
        double ux[kMaxZoneVertices], uy[kMaxZoneVertices];
        for (int k = 0; k < n; ++k) ux[k] = vx[corner_point[b + k]], uy[k] = vy[corner_point[b + k]];
        double dtz = 1e300;
        const double burn_z = any_burn ? burn[z] : 1.0;
        const std::int64_t code = with_geometry(rz, [&](auto g) {
          using G = decltype(g);
          return quads ? end_state<4, G>(z, v, ux, uy, zone_mass[z], e[z], burn_z, o, eos, m, out, dtz)
                       : end_state<0, G>(z, v, ux, uy, zone_mass[z], e[z], burn_z, o, eos, m, out, dtz);
        });
        if (!r.ghost) failure = std::min(failure, code);
        if (dtz < local.dt && !r.ghost) local = {dtz, z};
      }
#pragma omp critical
      merge_thread_choice(range_best, local);
    }
    merge_range_choice(best, range_best);
  });
  failure = agreed(*this, failure);
  if (failure != kNoFailure) throw_zone_failure(*this, failure, "in the initial or restored state");
  best = agreed(*this, best);
  dt_next = best.dt;
  dt_zone = best.zone;
}

// Z1 on the force geometry (px, py), or x^n + h_position v^n when px is null, with the
// velocity (qvx, qvy) for q and hourglass, the state advanced by dt_half from t^n, at time
// t_eval; writes the corner forces. Returns the lowest failing zone's code.
std::int64_t Simulation::Impl::zone_forces(const double* px, const double* py, double h_position, const double* qvx,
                                           const double* qvy, double dt_half, double t_eval) {
  const ZoneForceInput in{.zone_corner_begin = zone_corner_begin.data(),
                          .corner_point = corner_point.data(),
                          .px = px,
                          .py = py,
                          .h_position = h_position,
                          .x = x.data(),
                          .y = y.data(),
                          .vx = vx.data(),
                          .vy = vy.data(),
                          .qvx = qvx,
                          .qvy = qvy,
                          .f_prev_x = corner_fx.data(),
                          .f_prev_y = corner_fy.data(),
                          .zone_mass = zone_mass.data(),
                          .e = e.data(),
                          .sxx = data_or_null(sxx),
                          .syy = data_or_null(syy),
                          .sxy = data_or_null(sxy),
                          .plastic = data_or_null(plastic),
                          .grad_xx = data_or_null(grad_xx),
                          .grad_xy = data_or_null(grad_xy),
                          .grad_yx = data_or_null(grad_yx),
                          .grad_yy = data_or_null(grad_yy),
                          .burn = data_or_null(burn),
                          .lighting_time = data_or_null(lighting_time),
                          .burn_length = data_or_null(burn_length),
                          .energy_source = energy_source(*this),
                          .dt_half = dt_half,
                          .t_eval = t_eval,
                          .subzone_mass = data_or_null(corner_mass),
                          .heat_rate = data_or_null(heat_rate)};
  const ZoneForceOutput out{.fx = corner_fx.data(),
                            .fy = corner_fy.data(),
                            .q = q.data(),
                            .rho_half = data_or_null(rho_half),
                            .c_half = data_or_null(c_half),
                            .sxx_half = data_or_null(sxx_half),
                            .syy_half = data_or_null(syy_half),
                            .sxy_half = data_or_null(sxy_half)};
  const HydroOptions& o = problem.options;
  std::int64_t failure = kNoFailure;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const ZoneModel& m) {
    // The plain instantiation where it gives the same bits (zone_forces.hpp).
    const bool plain = plain_zone_forces(in, o, m);
    const std::int64_t code = with_geometry(rz, [&](auto g) {
      using G = decltype(g);
      if (plain)
        return all_quads ? zone_forces_loop<4, G, true>(in, o, m, eos, r.begin, r.end, out)
                         : zone_forces_loop<0, G, true>(in, o, m, eos, r.begin, r.end, out);
      return all_quads ? zone_forces_loop<4, G>(in, o, m, eos, r.begin, r.end, out)
                       : zone_forces_loop<0, G>(in, o, m, eos, r.begin, r.end, out);
    });
    if (!r.ghost) failure = std::min(failure, code);
  });
  return agreed(*this, failure);
}

// The edge viscosity's forces, added to the corner forces: geometry (px, py), velocity
// (qvx, qvy), and the density and sound speed Z1 left in rho_half, c_half.
void Simulation::Impl::edge_forces(const double* px, const double* py, const double* qvx, const double* qvy) {
  const HydroOptions& o = problem.options;
  const EdgeViscosityInput in{.zone_corner_begin = zone_corner_begin.data(),
                              .corner_point = corner_point.data(),
                              .continuation = continuation.data(),
                              .x = px,
                              .y = py,
                              .ux = qvx,
                              .uy = qvy,
                              .rho = rho_half.data(),
                              .C = c_half.data(),
                              .c1 = o.edge_c1,
                              .c2 = o.edge_c2,
                              .limiter = o.edge_limiter};
  for_each_range(*this, [&](const ZoneRange& r, const auto&, const ZoneModel& m) {
    edge_forces_loop(in, r.begin, r.end, m.edge_gamma_factor, corner_fx.data(), corner_fy.data());
  });
}

void Simulation::Impl::evaluate_forces_now() {
  const std::int64_t failure = zone_forces(x.data(), y.data(), 0.0, vx.data(), vy.data(), 0.0, t);
  if (failure != kNoFailure) throw_zone_failure(*this, failure, "while evaluating forces");
  if (edge_viscosity) edge_forces(x.data(), y.data(), vx.data(), vy.data());
  // A distributed run: the outermost ghosts' edge viscosity lacks neighbours; their owners' forces replace it.
  if (collective) collective->exchange(*this);
  if (rz) weight_rz_forces(x.data(), 0.0);
}

// rz: the area-weighted corner forces made true ones (docs/algorithm.md §19).
void Simulation::Impl::weight_rz_forces(const double* px, double h_position) {
  weight_rz_forces_loop(mesh().num_corners(), corner_point.data(), px, x.data(), vx.data(), h_position,
                        axis_points.size(), axis_points.data(), axis_corner_begin.data(), axis_corner.data(),
                        axis_ref_a.data(), axis_ref_b.data(), axis_moment.data(), corner_fx.data(), corner_fy.data(),
                        axis_ax.data(), axis_ay.data());
}

// The heat flux on the state at t^n (docs/algorithm.md §21): every zone's conductivity and
// centre, then its energy rate and time-step limit. The owned zones' values read only zones
// across their edges (ghost layer 1), exchanged after the last step, so they are the serial ones.
void Simulation::Impl::heat_flux_rates_now() {
  const HydroOptions& o = problem.options;
  const HeatFluxInput in{.zone_corner_begin = zone_corner_begin.data(),
                         .corner_point = corner_point.data(),
                         .neighbour = heat_neighbour.data(),
                         .x = x.data(),
                         .y = y.data(),
                         .vx = vx.data(),
                         .vy = vy.data(),
                         .rho = rho.data(),
                         .C = c.data(),
                         .e = e.data(),
                         .zone_mass = zone_mass.data(),
                         .c1 = o.heat_flux_c1,
                         .c2 = o.heat_flux_c2};
  const Index nz = mesh().num_zones();
  with_geometry(rz, [&](auto g) {
    heat_flux_conductivity<decltype(g)>(in, 0, nz, heat_kappa.data(), heat_cx.data(), heat_cy.data());
  });
  DtChoice choice, ghost_choice;
  for (const ZoneRange& r : ranges) {
    with_geometry(rz, [&](auto g) {
      heat_flux_rates<decltype(g)>(in, heat_kappa.data(), heat_cx.data(), heat_cy.data(), r.begin, r.end,
                                   kHeatFluxDtFraction, heat_rate.data(), r.ghost ? ghost_choice : choice);
    });
  }
  heat_dt = agreed(*this, choice);
}

// External point forces at the half step: applied pressures (boundary work) and momentum
// sources (source work), on the half-step geometry (docs/algorithm.md §10).
void Simulation::Impl::external_forces(double t_half) {
  pressure_forces(*this, x_half, y_half, t_half, ext_fx, ext_fy);
  if (!(problem.sources && problem.sources->momentum)) return;
  std::fill(src_fx.begin(), src_fx.end(), 0.0);
  std::fill(src_fy.begin(), src_fy.end(), 0.0);
  // Median-dual volume of each point on the half geometry: the sum of its corner areas.
  const Index nz = mesh().num_zones();
#pragma omp parallel for schedule(static) if (nz > kParallelMin)
  for (Index z = 0; z < nz; ++z) {
    const Index b = zone_corner_begin[z];
    const int n = zone_corner_begin[z + 1] - b;
    const ZoneVertices v = gather_vertices<0>(corner_point.data(), b, n, x_half.data(), y_half.data());
    Geometry::corner_areas(v, corner_scratch.data() + b);
  }
  const Index np = mesh().num_points();
  const auto& momentum = problem.sources->momentum;
#pragma omp parallel for schedule(static) if (np > kParallelMin)
  for (Index p = 0; p < np; ++p) {
    double vp = 0;
    for (Index k = point_corner_begin[p]; k < point_corner_begin[p + 1]; ++k) vp += corner_scratch[point_corners[k]];
    const auto f = momentum(x_half[p], y_half[p], t_half);
    src_fx[p] = vp * f[0];
    src_fy[p] = vp * f[1];
  }
  // Periodic copies of a point are one point: each copy holds part of its dual area, so the
  // group's force is the sum over its copies, shared among them by mass.
  for (const auto& group : periodic_groups) {
    double mass = 0, fx = 0, fy = 0;
    for (Index p : group) mass += point_mass[p], fx += src_fx[p], fy += src_fy[p];
    for (Index p : group) {
      src_fx[p] = fx * point_mass[p] / mass;
      src_fy[p] = fy * point_mass[p] / mass;
    }
  }
}

// P1 (steps 2, 4): x^{n+1/2} (when stored), v* = v^n + dt/2 (F_pred + F_ext)/M_p, constraints
// at t^{n+1/2}.
void Simulation::Impl::predict_velocity(double dt, double t_half) {
  const Index np = mesh().num_points();
  const double h = 0.5 * dt;
  predict_velocity_loop(point_input(*this), np, h, data_or_null(x_half), data_or_null(y_half), vx_star.data(),
                        vy_star.data());
  if (has_external) {
    external_forces(t_half);
    add_external_velocity(np, h, point_mass.data(), ext_fx.data(), ext_fy.data(), data_or_null(src_fx),
                          data_or_null(src_fy), vx_star.data(), vy_star.data());
  }
  if (rz)
    move_axis_points(axis_points.size(), axis_points.data(), h, axis_ax.data(), axis_ay.data(), vx.data(), vy.data(),
                     vx_star.data(), vy_star.data());
  apply_constraints(*this, vx_star, vy_star, t_half);
}

// P2 (step 6): v_free = v^n + dt (F^{n+1/2} + F_ext)/M_p; v^{n+1} = constraints(v_free) at
// t^{n+1}, keeping v_free of the constrained points for the constraint work. A compensated
// update (docs/algorithm.md §20) writes the low parts of v^{n+1}, constrained alike.
void Simulation::Impl::correct_velocity(double dt, double t_new) {
  const bool external = has_external;
  const VelocityLowParts lo{data_or_null(vx_lo), data_or_null(vy_lo), data_or_null(vx_lo_new), data_or_null(vy_lo_new)};
  correct_velocity_loop(point_input(*this), mesh().num_points(), dt, external ? ext_fx.data() : nullptr,
                        external ? ext_fy.data() : nullptr, external ? data_or_null(src_fx) : nullptr,
                        external ? data_or_null(src_fy) : nullptr, lo, vx_new.data(), vy_new.data());
  if (rz)
    move_axis_points(axis_points.size(), axis_points.data(), dt, axis_ax.data(), axis_ay.data(), vx.data(), vy.data(),
                     vx_new.data(), vy_new.data(), lo);
  for (std::size_t i = 0; i < constrained.size(); ++i) {
    free_vx[i] = vx_new[constrained[i]];
    free_vy[i] = vy_new[constrained[i]];
  }
  apply_constraints(*this, vx_new, vy_new, t_new);
  if (lo.x) constrain_low_parts(*this, vx_lo_new, vy_lo_new);
}

// Z2 (steps 7, 8, 9) over every range; on success the next dt candidate is in dt_next.
std::int64_t Simulation::Impl::end_of_step(double dt, double t_new) {
  const ZoneEndInput in{.zone_corner_begin = zone_corner_begin.data(),
                        .corner_point = corner_point.data(),
                        .x = x.data(),
                        .y = y.data(),
                        .x_lo = data_or_null(x_lo),
                        .y_lo = data_or_null(y_lo),
                        .x_half = data_or_null(x_half),
                        .y_half = data_or_null(y_half),
                        .vx = vx.data(),
                        .vy = vy.data(),
                        .ux = vx_new.data(),
                        .uy = vy_new.data(),
                        .fx = corner_fx.data(),
                        .fy = corner_fy.data(),
                        .zone_mass = zone_mass.data(),
                        .e = e.data(),
                        .sxx = data_or_null(sxx),
                        .syy = data_or_null(syy),
                        .sxy = data_or_null(sxy),
                        .sxx_half = data_or_null(sxx_half),
                        .syy_half = data_or_null(syy_half),
                        .sxy_half = data_or_null(sxy_half),
                        .plastic = data_or_null(plastic),
                        .burn = data_or_null(burn),
                        .lighting_time = data_or_null(lighting_time),
                        .burn_length = data_or_null(burn_length),
                        .energy_source = energy_source(*this),
                        .dt = dt,
                        .t_new = t_new,
                        .heat_rate = data_or_null(heat_rate)};
  const ZoneEndOutput out{.e_new = e_new.data(),
                          .source_energy = data_or_null(source_energy),
                          .sxx_new = data_or_null(sxx_new),
                          .syy_new = data_or_null(syy_new),
                          .sxy_new = data_or_null(sxy_new),
                          .plastic_new = data_or_null(plastic_new),
                          .burn_new = data_or_null(burn_new),
                          .state = state_output(*this)};
  const HydroOptions& o = problem.options;
  DtChoice choice, ghost_choice;
  std::int64_t failure = kNoFailure;
  for_each_range(*this, [&](const ZoneRange& r, const auto& eos, const ZoneModel& m) {
    DtChoice& target = r.ghost ? ghost_choice : choice;
    // The plain instantiation where it gives the same bits (zone_end.hpp).
    const bool plain = plain_zone_end(in, m);
    const std::int64_t code = with_geometry(rz, [&](auto g) {
      using G = decltype(g);
      if (plain)
        return all_quads ? end_of_step_loop<4, G, true>(in, o, m, eos, r.begin, r.end, out, target)
                         : end_of_step_loop<0, G, true>(in, o, m, eos, r.begin, r.end, out, target);
      return all_quads ? end_of_step_loop<4, G>(in, o, m, eos, r.begin, r.end, out, target)
                       : end_of_step_loop<0, G>(in, o, m, eos, r.begin, r.end, out, target);
    });
    if (!r.ghost) failure = std::min(failure, code);
  });
  failure = agreed(*this, failure);
  if (failure == kNoFailure) choice = agreed(*this, choice), dt_next = choice.dt, dt_zone = choice.zone;
  return failure;
}

// Step 6's energy bookkeeping: the work of the constraints, applied pressures and sources,
// with the same v_bar as the zones' energy update (docs/algorithm.md §10).
void Simulation::Impl::account_boundary_work(double dt) {
  // Exact sums over this rank's own points and zones (docs/parallel.md, "Determinism").
  const Index np = mesh().num_points();
  const unsigned char* ghost = ghost_point.empty() ? nullptr : ghost_point.data();
  std::array<ExactSum, 3> sums;  // constraint work, external work, source work
  constraint_work(constrained.size(), constrained.data(), ghost, point_mass.data(), vx.data(), vy.data(), vx_new.data(),
                  vy_new.data(), free_vx.data(), free_vy.data(), sums[0]);
  if (has_external)
    point_force_work(np, ghost, dt, vx.data(), vy.data(), vx_new.data(), vy_new.data(), ext_fx.data(), ext_fy.data(),
                     data_or_null(src_fx), data_or_null(src_fy), sums[1], sums[2]);
  for (std::size_t z = 0; z < source_energy.size(); ++z)
    if (ghost_zone.empty() || !ghost_zone[z]) sums[2].add(source_energy[z]);
  if (collective) collective->sum(sums);
  boundary_work += sums[0].value() + sums[1].value();
  source_work += sums[2].value();
}

// Commit: x^{n+1} = x^n + dt v_bar (the expression of Z2), then the new state replaces the old.
void Simulation::Impl::commit(double dt) {
  commit_loop(mesh().num_points(), dt, vx.data(), vy.data(), vx_new.data(), vy_new.data(), x.data(), y.data(),
              data_or_null(x_lo), data_or_null(y_lo));
  swap_new_into_current(*this, *this);  // v, e, S, plastic strain, burn, low parts (the state table)
  have_previous_forces = true;
}

bool Simulation::Impl::try_step(double dt) {
  const double t_half = t + 0.5 * dt, t_new = t + dt;
  // 1. Predictor forces f^{n-1/2} (the last corrector's, in corner_fx/fy), or f^n afresh.
  if (!have_previous_forces || problem.options.fresh_predictor) evaluate_forces_now();

  // 2, 4. P1: half-step positions and the predicted velocity v*.
  predict_velocity(dt, t_half);

  // 2, 3, 5. Z1: half-step geometry and state, corner forces f^{n+1/2}.
  const double* px = data_or_null(x_half);
  std::int64_t failure =
      zone_forces(px, data_or_null(y_half), 0.5 * dt, vx_star.data(), vy_star.data(), 0.5 * dt, t_half);
  if (failure != kNoFailure) {
    have_previous_forces = false;  // the corner forces now hold this failed attempt's
    if (failure_kind(failure) == kTangled) return false;
    throw_zone_failure(*this, failure, "at the half step");
  }
  // 5. Edge viscosity forces, added to f^{n+1/2}.
  if (edge_viscosity) edge_forces(x_half.data(), y_half.data(), vx_star.data(), vy_star.data());
  if (rz) weight_rz_forces(px, 0.5 * dt);  // rz: true corner forces from the area-weighted ones

  // 6. P2: momentum v^{n+1} with the same corner forces, and the constraints.
  correct_velocity(dt, t_new);

  // 7, 8, 9. Z2: energy, stress, end geometry, EOS, time-step candidates.
  failure = end_of_step(dt, t_new);
  if (failure != kNoFailure) {
    have_previous_forces = false;
    recompute_state();  // restore area, density, pressure of the start of the step
    if (failure_kind(failure) == kTangled) return false;
    throw_zone_failure(*this, failure, "at the end of the step");
  }
  // No point through a wall (docs/algorithm.md §10): retried like a tangled zone.
  Index crossing = step_wall_crossing(*this, dt);
  if (collective) crossing = collective->min_point(*this, crossing);  // every rank retries alike
  if (crossing >= 0) {
    have_previous_forces = false;
    recompute_state();
    return false;
  }

  // 6 (work). Work of the constraints, applied pressures and sources, for the audit.
  account_boundary_work(dt);

  // Commit: x^{n+1}, v^{n+1}, e^{n+1}, S^{n+1}, burn; a distributed run's ghosts get their owners' values.
  commit(dt);
  if (collective) collective->exchange(*this);
  t = t_new;
  ++cycle;
  dt_last = dt;
  return true;
}

void Simulation::Impl::step(double t_stop) {
  if (t_stop <= t) return;
  const HydroOptions& o = problem.options;
  // Time-step control (docs/algorithm.md §9): CFL and volume limits from the end of the last step,
  // growth limit, dt_max, first-step dt_init; land exactly on t_stop.
  // The heat flux's rates at t^n and its stability limit join the zones' candidates.
  double candidate = dt_next;
  bool heat_limited = false;
  if (heat_flux) {
    heat_flux_rates_now();
    heat_limited = heat_dt.dt < candidate;
    if (heat_limited) candidate = heat_dt.dt;
  }
  const DtControl control = control_time_step(candidate, dt_control_prev, cycle == 0, o.dt_growth, o.dt_init, o.dt_max);
  double dt = control.dt;
  switch (control.limit) {
    case DtLimit::cfl:
      dt_reason = heat_limited ? DtReason::heat_flux : DtReason::cfl;
      if (heat_limited) dt_zone = heat_dt.zone;
      break;
    case DtLimit::growth:
      dt_reason = DtReason::growth;
      break;
    case DtLimit::initial:
      dt_reason = DtReason::initial;
      break;
    case DtLimit::maximum:
      dt_reason = DtReason::maximum;
      break;
  }
  for (int attempt = 0;; ++attempt) {
    if (dt < dt_min) throw_dt_collapse(*this, dt);
    dt_control_prev = dt;
    const bool clipped = t + dt >= t_stop;
    const double dt_taken = clipped ? t_stop - t : dt;
    if (try_step(dt_taken)) {
      if (clipped) t = t_stop, dt_reason = DtReason::landing;  // land exactly
      break;
    }
    if (attempt >= o.max_retries) throw_tangled_step(*this, dt_taken, attempt);
    dt *= 0.5;
    dt_reason = DtReason::retry;
  }
  if (remap) {
    RemapState state{mesh(), t, cycle, x, y, vx, vy, e, sxx, syy, sxy, zone_mass, point_mass, area};
    if (remap->remap(state)) {
      // The remap placed the points and velocities anew: no round-off left to carry (§20).
      for (auto* lo : {&x_lo, &y_lo, &vx_lo, &vy_lo}) std::fill(lo->begin(), lo->end(), 0.0);
      // The built-in ALE remap charges its moves to the wall check's budgets (ale_remap.cpp):
      // they stay valid, and the next step tests only the points near a wall.
      const bool charged = std::exchange(wall_clearance.charged, false);
      recompute_state();
      wall_clearance.valid = charged;
    }
  }
  if (observer) observer(*owner);
}

// The lowest zone whose end-of-step geometry is tangled for a step of dt (diagnostics only).
Index Simulation::Impl::find_tangled_zone(double dt) {
  const Index nz = mesh().num_zones();
  for (Index z = 0; z < nz; ++z) {
    if (!ghost_zone.empty() && ghost_zone[z]) continue;
    const Index b = zone_corner_begin[z];
    const int n = zone_corner_begin[z + 1] - b;
    // End positions of the failed attempt (v_new is still its velocity).
    ZoneVertices v;
    v.n = n;
    for (int k = 0; k < n; ++k) {
      const Index p = corner_point[b + k];
      v.x[k] = advanced(x[p], dt * 0.5 * (vx[p] + vx_new[p]), data_or_null(x_lo), p);
      v.y[k] = advanced(y[p], dt * 0.5 * (vy[p] + vy_new[p]), data_or_null(y_lo), p);
    }
    double ca[kMaxZoneVertices];
    const double smallest_corner = Geometry::corner_areas(v, ca);
    if (!(Geometry::area(v) > 0) || edges_cross(v) || (problem.options.check_corner_areas && !(smallest_corner > 0)))
      return z;
  }
  return -1;
}

// The totals are exact sums, rounded once: the same for any thread count, any order and any
// number of ranks (docs/parallel.md, "Determinism"); a rank sums its own points and zones.
double Simulation::Impl::kinetic_energy() const {
  const Index np = mesh().num_points();
  std::array<ExactSum, 1> sum;
  for (Index p = 0; p < np; ++p)
    if (ghost_point.empty() || !ghost_point[p]) sum[0].add(0.5 * point_mass[p] * (vx[p] * vx[p] + vy[p] * vy[p]));
  if (collective) collective->sum(sum);
  return sum[0].value();
}

double Simulation::Impl::internal_energy() const {
  const Index nz = mesh().num_zones();
  std::array<ExactSum, 1> sum;
  for (Index z = 0; z < nz; ++z)
    if (ghost_zone.empty() || !ghost_zone[z]) sum[0].add(zone_mass[z] * e[z]);
  if (collective) collective->sum(sum);
  return sum[0].value();
}

}  // namespace stagger
