// describe(): the resolved set-up in words, for `stagger check` and the run's log.
#include <cmath>
#include <sstream>

#include "scene_internal.hpp"
#include "stagger/option_table.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

namespace {

const char* kind_name(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::wall:
      return "wall (v.n = 0)";
    case BoundaryKind::velocity:
      return "prescribed velocity";
    case BoundaryKind::free:
      return "free (traction-free)";
    case BoundaryKind::pressure:
      return "applied pressure";
    case BoundaryKind::periodic:
      return "periodic";
    case BoundaryKind::transmitting:
      return "transmitting (p = p0 + rho c u.n)";
    case BoundaryKind::fixed:
      return "fixed (v = 0, clamped)";
  }
  return "?";
}

// The EOS and its constants, named as in the scene (the option tables' echo).
std::string eos_text(const EquationOfState& eos) {
  if (const auto* gas = std::get_if<IdealGas>(&eos)) return "ideal gas, " + ideal_gas_option_table().echo(*gas);
  if (const auto* mg = std::get_if<MieGruneisen>(&eos))
    return "Mie-Gruneisen, " + mie_gruneisen_option_table().echo(*mg);
  if (const auto* jwl = std::get_if<Jwl>(&eos)) return "JWL, " + jwl_option_table().echo(*jwl);
  if (const auto* sg = std::get_if<StiffenedGas>(&eos))
    return "stiffened gas, " + stiffened_gas_option_table().echo(*sg);
  return "?";
}

// "  " + the option table's echo, wrapped after a comma at about 100 columns.
std::string echo_lines(const std::string& echo) {
  std::string out = "  ";
  std::size_t width = 2;
  std::size_t start = 0;
  while (start < echo.size()) {
    std::size_t comma = echo.find(", ", start);
    const std::string item = echo.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (width > 2 && width + item.size() + 2 > 100) {
      out += ",\n  ";
      width = 2;
    } else if (width > 2) {
      out += ", ";
      width += 2;
    }
    out += item;
    width += item.size();
    start = comma == std::string::npos ? echo.size() : comma + 2;
  }
  return out + "\n";
}

// The volume per radian of zone z in rz: the integral of x dA over it (Pappus: the area
// times the radius of its centroid).
double volume_per_radian(const Mesh& mesh, Index z) {
  double sum = 0;
  const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
  for (Index c = begin; c < end; ++c) {
    const Index a = mesh.corner_point[c], b = mesh.corner_point[c + 1 < end ? c + 1 : begin];
    sum += (mesh.x[a] + mesh.x[b]) * (mesh.x[a] * mesh.y[b] - mesh.x[b] * mesh.y[a]);
  }
  return sum / 6;
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
  out << "  time: " << time_option_table().echo(problem) << "\n";

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
    if (material.strength) out << "    strength: " << strength_echo(*material.strength) << "\n";
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
    // rz: per radian, as the run's masses and energies (docs/algorithm.md §19), and the whole.
    const bool rz = options.geometry == CoordinateSystem::rz;
    double mass = 0;
    if (r >= 0)
      for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z) {
        const auto centre = zone_centre(mesh, z);
        mass += region.density(centre[0], centre[1]) * (rz ? volume_per_radian(mesh, z) : zone_area(mesh, z));
      }
    out << "  " << region.region << ": material " << region.material << ", " << zones << " zones, mass ~ " << mass;
    if (rz) out << " per radian (" << 2 * M_PI * mass << " in the full 2 pi)";
    out << (region.pressure ? ", pressure given" : ", specific internal energy given")
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
    out << "energy deposit: " << deposit_option_table().echo(deposit) << "\n";
  if (problem.sources) out << "manufactured source terms: on\n";

  out << "numerics\n" << echo_lines(numerics_option_table().echo(options));
  if (problem.ale.mode != AleMode::lagrangian) out << "ale\n" << echo_lines(ale_option_table().echo(problem.ale));
  out << "output " << control.output_directory << ", reference " << (control.reference ? "yes" : "none") << "\n"
      << echo_lines(output_option_table().echo(control));
  return out.str();
}

}  // namespace stagger
