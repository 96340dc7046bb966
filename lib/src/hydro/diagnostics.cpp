// The step's messages (docs/robustness.md): what a failed zone, a collapsed time step or a
// tangled step tells the user, naming the zone or point by its serial number and the remedies
// the scene has not already taken.
#include "hydro/diagnostics.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "hydro/boundary.hpp"
#include "hydro/kernels/zone_status.hpp"
#include "stagger/error.hpp"

namespace stagger {

std::string describe_zone(const Simulation::Impl& s, Index z) {
  const Mesh& m = s.mesh();
  std::ostringstream out;
  // A distributed run names the zone and its points by their global (serial) numbers.
  out << "zone " << (s.global_zone.empty() ? z : s.global_zone[z]) << " (region '" << m.region_names[m.zone_region[z]]
      << "', points";
  for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
    const Index p = m.corner_point[c];
    out << ' ' << (s.global_point.empty() ? p : s.global_point[p]) << " (" << s.x[p] << ", " << s.y[p] << ")";
  }
  out << ")";
  return out.str();
}

namespace {

std::string zone_failure_message(const Simulation::Impl& s, Index z, int kind, const std::string& what_step) {
  std::ostringstream msg;
  msg << "cycle " << s.cycle << ", t = " << s.t << ": " << describe_zone(s, z);
  if (kind == kEosDomain) {
    msg << " left the domain of its equation of state " << what_step << " (start-of-step density " << s.rho[z]
        << ", specific internal energy " << s.e[z] << "): the zone is over-compressed or over-expanded";
  } else if (kind == kNotFinite) {
    msg << " has a non-finite state (NaN or Inf) " << what_step;
  } else {
    msg << " has a non-positive area " << what_step;
  }
  return msg.str();
}

}  // namespace

// `code` is an agreed code (global zone numbers in a distributed run, whose owner words it).
void throw_zone_failure(const Simulation::Impl& s, std::int64_t code, const std::string& what_step) {
  const int kind = failure_kind(code);
  const auto text = [&](Index z) { return zone_failure_message(s, z, kind, what_step); };
  throw Error(s.collective ? s.collective->zone_text(s, failure_zone(code), text) : text(failure_zone(code)));
}

// Remedies for a tangled step that the scene has not already taken (docs/algorithm.md §9).
std::string tangling_remedies(const HydroOptions& o, AleMode ale_mode) {
  std::vector<std::string> tips;
  if (o.hourglass != Hourglass::subzonal_triangles)
    tips.push_back(
        "numerics.hourglass = \"subzonal_triangles\" with hourglass_coefficient = 2 (docs/algorithm.md §18)");
  else if (o.hourglass_coefficient < 2)
    tips.push_back("a larger numerics.hourglass_coefficient (2 is measured to hold a blast in a box)");
  if (o.cfl > 0.1) tips.push_back("a lower numerics.cfl");
  if (o.viscosity != Viscosity::edge && o.q1 < 2) tips.push_back("a larger numerics.q1");
  tips.push_back("a finer or better-shaped mesh near the zone");
  if (ale_mode == AleMode::lagrangian) tips.push_back("ale.mode = \"ale\" (rezone and remap, docs/ale.md)");
  std::string text = "try ";
  for (std::size_t i = 0; i < tips.size(); ++i) text += (i == 0 ? "" : i + 1 == tips.size() ? " or " : ", ") + tips[i];
  return text;
}

// dt below dt_min: the limiting zone and what to do.
void throw_dt_collapse(const Simulation::Impl& s, double dt) {
  std::ostringstream msg;
  msg << "time step collapsed at cycle " << s.cycle << ", t = " << s.t << ": dt = " << dt << " < dt_min = " << s.dt_min;
  const auto limiting = [&](Index z) {
    std::ostringstream text;
    text << "; limiting " << describe_zone(s, z) << ", area " << s.area[z] << ", sound speed " << s.c[z] << ", density "
         << s.rho[z];
    return text.str();
  };
  if (s.collective && s.dt_zone >= 0)
    msg << s.collective->zone_text(s, s.dt_zone, limiting);  // dt_zone is global
  else if (s.dt_zone >= 0 && s.dt_zone < s.mesh().num_zones())
    msg << limiting(s.dt_zone);
  msg << " (the mesh is tangling or a zone is being crushed: refine the mesh, lower the cfl, or raise the "
         "viscosity)";
  throw Error(msg.str());
}

// A step still tangled after the retries: the tangled zone, or the point through a wall.
void throw_tangled_step(Simulation::Impl& s, double dt_taken, int attempt) {
  const HydroOptions& o = s.problem.options;
  std::ostringstream msg;
  Index tangled = s.find_tangled_zone(dt_taken);
  // A distributed run: the lowest tangled zone over the ranks (global), worded by its owner.
  const std::int64_t tangled_code =
      s.collective ? s.collective->min_failure(s, tangled >= 0 ? failure_code(tangled, 0) : kNoFailure) : 0;
  if (s.collective) tangled = tangled_code != kNoFailure ? failure_zone(tangled_code) : -1;
  Index p = tangled < 0 ? find_wall_crossing(s, dt_taken) : -1;
  if (s.collective && tangled < 0) p = s.collective->min_point(s, p);
  if (p >= 0) {
    const auto crossing_text = [&](Index q) { return describe_wall_crossing(s, q, dt_taken); };
    msg << "cycle " << s.cycle << ", t = " << s.t << ": "
        << (s.collective ? s.collective->point_text(s, p, crossing_text) : crossing_text(p))
        << " even with dt = " << dt_taken << " after " << attempt << " retries (the mesh is folding against the "
        << "wall; " << tangling_remedies(o, s.problem.ale.mode) << ")";
    throw Error(msg.str());
  }
  msg << "cycle " << s.cycle << ", t = " << s.t
      << ": a zone tangled (non-positive area, crossing edges or a folded corner) even with dt = " << dt_taken
      << " after " << attempt << " retries";
  const auto describe = [&](Index z) { return "; " + describe_zone(s, z); };
  if (s.collective) {
    if (tangled >= 0) msg << s.collective->zone_text(s, tangled, describe);  // tangled is global
  } else if (tangled >= 0) {
    msg << describe(tangled);
  }
  msg << " (the mesh is folding there; " << tangling_remedies(o, s.problem.ale.mode) << ")";
  throw Error(msg.str());
}

}  // namespace stagger
