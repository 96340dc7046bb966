// describe(): the resolved set-up in words, for `stagger check` and the run's log.
#include <cmath>
#include <sstream>

#include "scene_internal.hpp"

namespace stagger {

namespace {

const char* kind_name(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::wall: return "wall (v.n = 0)";
    case BoundaryKind::velocity: return "prescribed velocity";
    case BoundaryKind::free: return "free (traction-free)";
    case BoundaryKind::pressure: return "applied pressure";
    case BoundaryKind::periodic: return "periodic";
  }
  return "?";
}

std::string eos_text(const EquationOfState& eos) {
  std::ostringstream text;
  if (const auto* gas = std::get_if<IdealGas>(&eos)) text << "ideal gas, gamma = " << gas->gamma;
  if (const auto* mg = std::get_if<MieGruneisen>(&eos))
    text << "Mie-Gruneisen, rho0 = " << mg->rho0 << ", a0 = " << mg->a0 << ", Gamma0 = " << mg->gamma0
         << ", s = " << mg->s;
  if (const auto* jwl = std::get_if<Jwl>(&eos))
    text << "JWL, A = " << jwl->A << ", B = " << jwl->B << ", R1 = " << jwl->R1 << ", R2 = " << jwl->R2
         << ", omega = " << jwl->omega << ", rho0 = " << jwl->rho0;
  return text.str();
}

}  // namespace

std::string describe(const Scene& scene) {
  const Problem& problem = scene.problem;
  const Mesh& mesh = problem.mesh;
  const RunControl& control = scene.control;
  const HydroOptions& options = problem.options;
  std::ostringstream out;
  out.precision(6);
  out << "scene " << problem.name << " (" << scene.file << ")\n";
  out << "  t_end = " << problem.t_end << "\n";

  const MeshQuality quality = mesh_quality(mesh);
  out << "mesh " << mesh.source << ": " << mesh.num_zones() << " zones (" << quality.quads << " quads, "
      << quality.triangles << " triangles, " << quality.other_polygons << " other polygons), " << mesh.num_points()
      << " points\n";
  out << "  area " << quality.min_area << " .. " << quality.max_area << ", max aspect ratio "
      << quality.max_aspect_ratio << ", min angle " << quality.min_angle_degrees << " deg, non-convex zones "
      << quality.non_convex_zones << "\n";
  for (const auto& note : scene.notes) out << "  note: " << note << "\n";

  out << "materials\n";
  for (const auto& material : problem.materials) {
    out << "  " << material.name << ": " << eos_text(material.eos) << "\n";
    if (material.strength)
      out << "    strength: shear modulus " << material.strength->shear_modulus << ", yield stress "
          << material.strength->yield_stress << "\n";
    if (material.burn) {
      const Burn& burn = *material.burn;
      out << "    burn: D = " << burn.detonation_speed << ", " << burn.points.size() << " detonation point(s)"
          << (burn.plane ? ", detonation plane" : "") << (burn.beta_burn ? ", beta burn" : "") << "\n";
    }
  }

  out << "regions\n";
  for (const auto& region : problem.regions) {
    const int r = mesh.region_index(region.region);
    const Index zones = r >= 0 ? mesh.region_zone_begin[r + 1] - mesh.region_zone_begin[r] : 0;
    double mass = 0;
    if (r >= 0)
      for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z) {
        const auto centre = scene_detail::zone_centre(mesh, z);
        mass += region.density(centre[0], centre[1]) * zone_area(mesh, z);
      }
    out << "  " << region.region << ": material " << region.material << ", " << zones << " zones, mass ~ " << mass
        << (region.pressure ? ", pressure given" : ", specific internal energy given")
        << (region.stress_xx ? ", initial stress" : "") << "\n";
  }

  out << "boundaries\n";
  for (const auto& tag : mesh.tags) {
    out << "  " << tag.name << " (" << tag.edges.size() << " edges): ";
    bool found = false;
    for (const auto& condition : problem.boundaries) {
      if (condition.tag == tag.name) {
        out << kind_name(condition.kind);
        if (condition.kind == BoundaryKind::velocity)
          out << " u(0) = (" << condition.velocity_x(0) << ", " << condition.velocity_y(0) << ")";
        if (condition.kind == BoundaryKind::pressure) out << " p(0) = " << condition.pressure(0);
        if (condition.kind == BoundaryKind::periodic) out << " with " << condition.partner;
        found = true;
      } else if (condition.kind == BoundaryKind::periodic && condition.partner == tag.name) {
        out << "periodic with " << condition.tag;
        found = true;
      }
    }
    if (!found) out << "(none)";
    out << "\n";
  }
  for (const auto& deposit : problem.deposits)
    out << "energy deposit " << deposit.energy << " at (" << deposit.x << ", " << deposit.y << ")\n";
  if (problem.sources) out << "manufactured source terms: on\n";

  out << "numerics\n";
  out << "  cfl " << options.cfl << ", viscosity ";
  if (options.viscosity == Viscosity::bulk)
    out << "bulk (q1 " << options.q1 << ", q2 " << options.q2 << ")";
  else
    out << "edge (c1 " << options.edge_c1 << ", c2 " << options.edge_c2 << ", limiter "
        << (options.edge_limiter ? "on" : "off") << ")";
  out << ", hourglass "
      << (options.hourglass == Hourglass::gamma                 ? "gamma"
          : options.hourglass == Hourglass::flanagan_belytschko ? "flanagan_belytschko"
          : options.hourglass == Hourglass::subzonal            ? "subzonal"
                                                                : "subzonal_triangles")
      << " Q "
      << options.hourglass_coefficient << "\n";
  out << "  stress update " << (options.stress_update == StressUpdate::rate ? "rate" : "objective")
      << ", predictor " << (options.fresh_predictor ? "fresh" : "lagged") << ", volume limit " << options.volume_limit
      << ", dt growth " << options.dt_growth << ", dt_init " << options.dt_init << ", dt_max " << options.dt_max
      << ", dt_min " << options.dt_min << ", max retries " << options.max_retries << "\n";

  out << "output " << control.output_directory << "\n";
  out << "  dumps " << (control.dumps ? "on" : "off");
  if (control.dumps) {
    if (control.dump_interval > 0)
      out << " (every " << control.dump_interval << ")";
    else
      out << " (first and last)";
  }
  out << ", history every " << control.history_every << " cycle(s), checkpoints ";
  if (control.checkpoints)
    out << "every " << control.checkpoint_every_cycles << " cycles / " << control.checkpoint_every_seconds << " s";
  else
    out << "off";
  out << ", reference " << (control.reference ? "yes" : "none") << "\n";
  return out.str();
}

}  // namespace stagger
