// Whole-scene review: the first time step and the dump count against the settings, and
// the warnings for set-ups that make no sense (docs/scenes.md "Warnings").
#include "warnings.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "hydro/boundary_checks.hpp"
#include "scene_internal.hpp"
#include "stagger/error.hpp"
#include "strength/strength_models.hpp"

namespace stagger::scene_detail {

namespace {

// The mesh point nearest to (x, y) (the lowest index among equals).
Index nearest_point(const Mesh& mesh, double x, double y) {
  Index nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (Index p = 0; p < mesh.num_points(); ++p) {
    const double d = std::hypot(mesh.x[p] - x, mesh.y[p] - y);
    if (d < best) best = d, nearest = p;
  }
  return nearest;
}

std::string point_text(double x, double y) {
  std::ostringstream out;
  out.precision(6);
  out << "(" << x << ", " << y << ")";
  return out.str();
}

// "FILE:LINE: key 'path'" for a key of the document (the line of its table if absent).
class Locator {
 public:
  Locator(const toml::table& document, std::string file) : document_(document), file_(std::move(file)) {}
  std::string at(const std::string& path) const {
    const toml::node* node = document_.at_path(path).node();
    const toml::node* fallback = nullptr;
    for (std::string parent = path; !node && !fallback;) {
      const auto dot = parent.find_last_of(".[");
      if (dot == std::string::npos) break;
      parent.resize(dot);
      fallback = document_.at_path(parent).node();
    }
    return where(file_, node, fallback) + ": key '" + path + "'";
  }
  bool has(const std::string& path) const { return document_.at_path(path).node() != nullptr; }

 private:
  const toml::table& document_;
  std::string file_;
};

// The state at t = 0 of one zone, as the set-up will compute it (docs/algorithm.md §12).
struct ZoneState {
  double rho = 0, c = 0, speed = 0, length = 0;  // c: with the elastic part (as the time step)
  double bulk = 0;                               // rho c^2 of the EOS alone
  double centre_x = 0, centre_y = 0;
  int region = -1, material = -1;  // indices into problem.regions / problem.materials
};

double longest_chord(const Mesh& mesh, Index z) {
  double longest2 = 0;
  const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
  for (Index a = begin; a < end; ++a)
    for (Index b = a + 1; b < end; ++b) {
      const double dx = mesh.x[mesh.corner_point[b]] - mesh.x[mesh.corner_point[a]];
      const double dy = mesh.y[mesh.corner_point[b]] - mesh.y[mesh.corner_point[a]];
      longest2 = std::max(longest2, dx * dx + dy * dy);
    }
  return std::sqrt(longest2);
}

std::vector<ZoneState> initial_states(const Problem& problem) {
  const Mesh& mesh = problem.mesh;
  std::vector<int> setup_of_region(mesh.num_regions(), -1), material_of_setup(problem.regions.size(), -1);
  for (std::size_t i = 0; i < problem.regions.size(); ++i) {
    const int r = mesh.region_index(problem.regions[i].region);
    if (r >= 0) setup_of_region[r] = static_cast<int>(i);
    for (std::size_t m = 0; m < problem.materials.size(); ++m)
      if (problem.materials[m].name == problem.regions[i].material) material_of_setup[i] = static_cast<int>(m);
  }
  std::vector<ZoneState> states(mesh.num_zones());
  std::vector<double> point_speed(mesh.num_points(), std::numeric_limits<double>::quiet_NaN());
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    ZoneState& s = states[z];
    s.region = setup_of_region[mesh.zone_region[z]];
    if (s.region < 0 || material_of_setup[s.region] < 0) continue;
    s.material = material_of_setup[s.region];
    const RegionSetup& setup = problem.regions[s.region];
    const Material& material = problem.materials[s.material];
    const auto centre = zone_centre(mesh, z);
    s.centre_x = centre[0];
    s.centre_y = centre[1];
    s.rho = setup.density(centre[0], centre[1]);
    double e = 0;
    try {
      e = setup.specific_internal_energy
              ? setup.specific_internal_energy(centre[0], centre[1])
              : eos_energy_from_pressure(material.eos, s.rho, setup.pressure(centre[0], centre[1]));
      const double c2 = std::max(eos_sound_speed_squared(material.eos, s.rho, e), 0.0);
      s.bulk = s.rho * c2;
      const double elastic = material.strength ? (4.0 / 3.0) * shear_modulus(*material.strength, {}) / s.rho : 0.0;
      s.c = std::sqrt(c2 + elastic);
    } catch (const Error&) {
      s.c = 0;  // the reader has checked the EOS domain; nothing to estimate here
    }
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index k = begin; k < end; ++k) {
      // Each point once, with the first zone's region that reaches it (as the set-up does
      // for points shared by regions, up to the order): half the expression evaluations.
      const Index p = mesh.corner_point[k];
      if (std::isnan(point_speed[p])) {
        const double vx = setup.velocity_x ? setup.velocity_x(mesh.x[p], mesh.y[p]) : 0.0;
        const double vy = setup.velocity_y ? setup.velocity_y(mesh.x[p], mesh.y[p]) : 0.0;
        point_speed[p] = std::hypot(vx, vy);
      }
      s.speed = std::max(s.speed, point_speed[p]);
    }
    const double chord = longest_chord(mesh, z);
    s.length = chord > 0 ? zone_area(mesh, z) / chord : 0;  // the CFL length (docs/algorithm.md §9)
  }
  return states;
}

// A speed the drivers of the problem impose from outside the initial state (a cold gas at
// rest has no sound speed to set a time step): boundary velocities, sqrt(p / rho) of applied
// pressures, detonation speeds, and sqrt(2 E / m) of deposits into the zones around their
// point. Added to every zone's signal speed, it keeps the cycle estimate an upper bound.
double driver_speed(const Problem& problem, const std::vector<ZoneState>& states) {
  const Mesh& mesh = problem.mesh;
  double rho_min = std::numeric_limits<double>::infinity();
  for (const ZoneState& s : states)
    if (s.rho > 0) rho_min = std::min(rho_min, s.rho);
  double speed = 0;
  for (const auto& bc : problem.boundaries)
    for (int i = 0; i <= 20; ++i) {
      const double t = problem.t_end * i / 20.0;
      if (bc.kind == BoundaryKind::velocity) speed = std::max(speed, std::hypot(bc.velocity_x(t), bc.velocity_y(t)));
      if (bc.kind == BoundaryKind::pressure && std::isfinite(rho_min))
        speed = std::max(speed, std::sqrt(std::abs(bc.pressure(t)) / rho_min));
    }
  for (const auto& material : problem.materials)
    if (material.burn) speed = std::max(speed, material.burn->detonation_speed);
  for (const auto& deposit : problem.deposits) {
    if (deposit.radius > 0) {
      // A Gaussian: the largest specific energy, at the zone nearest to its centre.
      double total = 0, peak = 0;
      for (Index z = 0; z < mesh.num_zones(); ++z) {
        const auto [cx, cy] = zone_centre(mesh, z);
        const double r = std::hypot(cx - deposit.x, cy - deposit.y) / deposit.radius;
        total += states[z].rho * zone_area(mesh, z) * std::exp(-r * r);
        peak = std::max(peak, std::exp(-r * r));
      }
      if (total > 0) speed = std::max(speed, std::sqrt(2 * deposit.energy * peak / total));
      continue;
    }
    const Index nearest = nearest_point(mesh, deposit.x, deposit.y);
    double mass = 0;
    for (Index c = mesh.point_corner_begin[nearest]; c < mesh.point_corner_begin[nearest + 1]; ++c) {
      const Index z = mesh.corner_zone[mesh.point_corners[c]];
      mass += states[z].rho * zone_area(mesh, z);
    }
    if (mass > 0) speed = std::max(speed, std::sqrt(2 * deposit.energy / mass));
  }
  return std::isfinite(speed) ? speed : 0.0;
}

// Boundary edges (used by one zone only) that no tag covers.
struct Untagged {
  std::size_t count = 0;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // bounding box of their midpoints
  std::vector<std::array<double, 2>> examples;
};

Untagged untagged_boundary_edges(const Mesh& mesh) {
  // Every zone side as a sorted key (a, b) with a < b; a side in one zone only is on the
  // boundary. Sorting a flat array: 10^6 zones take a fraction of a second.
  auto key = [](Index a, Index b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  std::vector<std::uint64_t> sides;
  sides.reserve(mesh.corner_point.size());
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
    for (Index c = begin; c < end; ++c)
      sides.push_back(key(mesh.corner_point[c], mesh.corner_point[c + 1 < end ? c + 1 : begin]));
  }
  std::sort(sides.begin(), sides.end());
  std::vector<std::uint64_t> tagged;
  for (const auto& tag : mesh.tags)
    for (const auto& edge : tag.edges) tagged.push_back(key(edge[0], edge[1]));
  std::sort(tagged.begin(), tagged.end());
  std::vector<std::pair<Index, Index>> boundary;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    if (j - i == 1 && !std::binary_search(tagged.begin(), tagged.end(), sides[i]))
      boundary.emplace_back(static_cast<Index>(sides[i] >> 32), static_cast<Index>(sides[i] & 0xffffffffu));
    i = j;
  }
  Untagged result;
  for (const auto& edge : boundary) {
    const double mx = 0.5 * (mesh.x[edge.first] + mesh.x[edge.second]);
    const double my = 0.5 * (mesh.y[edge.first] + mesh.y[edge.second]);
    if (result.count == 0) result.x0 = result.x1 = mx, result.y0 = result.y1 = my;
    result.x0 = std::min(result.x0, mx), result.x1 = std::max(result.x1, mx);
    result.y0 = std::min(result.y0, my), result.y1 = std::max(result.y1, my);
    if (result.examples.size() < 3) result.examples.push_back({mx, my});
    ++result.count;
  }
  return result;
}

// The [[boundary]] key that names `tag`: "boundary[i].tag", "boundary[i].tags" or
// "boundary[i].partner"; "boundary" if none does.
std::string boundary_key(const toml::table& document, const std::string& tag) {
  const toml::array* sections = document["boundary"].as_array();
  for (std::size_t i = 0; sections && i < sections->size(); ++i) {
    const toml::table* section = sections->get(i)->as_table();
    if (!section) continue;
    const std::string path = "boundary[" + std::to_string(i) + "].";
    if (section->get("tag") && section->get("tag")->value<std::string>() == tag) return path + "tag";
    if (const toml::array* tags = section->get("tags") ? section->get("tags")->as_array() : nullptr)
      for (const toml::node& name : *tags)
        if (name.value<std::string>() == tag) return path + "tags";
  }
  for (std::size_t i = 0; sections && i < sections->size(); ++i) {
    const toml::table* section = sections->get(i)->as_table();
    if (section && section->get("partner") && section->get("partner")->value<std::string>() == tag)
      return "boundary[" + std::to_string(i) + "].partner";
  }
  return "boundary";
}

// Why the chosen [ale] mode never reads `key` (empty if it does; docs/ale.md, "Modes").
std::string dead_ale_key(const AleOptions& ale, bool mode_given, const std::string& key) {
  if (key == "mode") return {};
  if (ale.mode == AleMode::lagrangian)
    return mode_given ? "is ignored: mode = \"lagrangian\" never rezones or remaps; set mode = \"ale\" (or "
                        "\"eulerian\") or remove the key"
                      : "is ignored: [ale] has no mode, so the run is Lagrangian (no rezone, no remap); add mode = "
                        "\"ale\" (or \"eulerian\") or remove the key";
  if (ale.mode == AleMode::eulerian && key != "limiter")
    return key == "remap_every" || key == "quality_trigger"
               ? "is ignored: mode = \"eulerian\" remaps after every cycle; it is read by mode = \"ale\" only"
               : "is ignored: mode = \"eulerian\" returns to the initial mesh (no rezone); it is read by mode = "
                 "\"ale\" only";
  if (ale.mode == AleMode::ale && key == "size_weight" && ale.rezone != AleRezone::reference_jacobian)
    return "is ignored: it weighs a term of rezone = \"reference_jacobian\" only";
  return {};
}

// Points shared by regions whose initial velocities differ there: the first [[region]] in
// the file gives them its velocity (set_initial_velocities). The warning names the later
// region of the first such point, the count and the largest difference.
struct VelocityConflict {
  std::size_t count = 0, first_region = 0, later_region = 0;
  double x = 0, y = 0, difference = 0;
};

VelocityConflict shared_point_velocities(const Problem& problem) {
  const Mesh& mesh = problem.mesh;
  const Index np = mesh.num_points();
  std::vector<int> first(np, -1);
  std::vector<double> ux(np, 0), uy(np, 0);
  std::vector<char> counted(np, 0);
  VelocityConflict conflict;
  const auto velocity = [](const SpaceFunction& f, double x, double y) { return f ? f(x, y) : 0.0; };
  for (std::size_t i = 0; i < problem.regions.size(); ++i) {
    const RegionSetup& setup = problem.regions[i];
    const int r = mesh.region_index(setup.region);
    if (r < 0) continue;
    for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z)
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
        const Index p = mesh.corner_point[c];
        if (first[p] < 0) {
          first[p] = static_cast<int>(i);
          ux[p] = velocity(setup.velocity_x, mesh.x[p], mesh.y[p]);
          uy[p] = velocity(setup.velocity_y, mesh.x[p], mesh.y[p]);
          continue;
        }
        if (first[p] == static_cast<int>(i) || counted[p]) continue;
        const double vx = velocity(setup.velocity_x, mesh.x[p], mesh.y[p]);
        const double vy = velocity(setup.velocity_y, mesh.x[p], mesh.y[p]);
        const double d = std::hypot(vx - ux[p], vy - uy[p]);
        if (!(d > 1e-12 * std::max(std::hypot(vx, vy), std::hypot(ux[p], uy[p])))) continue;
        counted[p] = 1;
        if (conflict.count++ == 0)
          conflict.first_region = static_cast<std::size_t>(first[p]), conflict.later_region = i, conflict.x = mesh.x[p],
          conflict.y = mesh.y[p];
        conflict.difference = std::max(conflict.difference, d);
      }
  }
  return conflict;
}

// (x, y) inside zone z (the crossing-number test).
bool zone_contains(const Mesh& mesh, Index z, double x, double y) {
  bool inside = false;
  const Index begin = mesh.zone_corner_begin[z], end = mesh.zone_corner_begin[z + 1];
  for (Index c = begin; c < end; ++c) {
    const Index a = mesh.corner_point[c], b = mesh.corner_point[c + 1 < end ? c + 1 : begin];
    if ((mesh.y[a] > y) != (mesh.y[b] > y) &&
        x < mesh.x[a] + (y - mesh.y[a]) * (mesh.x[b] - mesh.x[a]) / (mesh.y[b] - mesh.y[a]))
      inside = !inside;
  }
  return inside;
}

// A deposit whose point lies outside the mesh by more than the zones there are wide (and, for
// a Gaussian, three radii): its energy would land in the zones around the nearest point.
void check_deposits(const Problem& problem, const Locator& key) {
  const Mesh& mesh = problem.mesh;
  for (std::size_t k = 0; k < problem.deposits.size(); ++k) {
    const EnergyDeposit& deposit = problem.deposits[k];
    bool inside = false;
    for (Index z = 0; z < mesh.num_zones() && !inside; ++z) inside = zone_contains(mesh, z, deposit.x, deposit.y);
    if (inside) continue;
    const Index nearest = nearest_point(mesh, deposit.x, deposit.y);
    const double best = std::hypot(mesh.x[nearest] - deposit.x, mesh.y[nearest] - deposit.y);
    double width = 0;
    for (Index j = mesh.point_corner_begin[nearest]; j < mesh.point_corner_begin[nearest + 1]; ++j)
      width = std::max(width, longest_chord(mesh, mesh.corner_zone[mesh.point_corners[j]]));
    const double reach = width + 3 * deposit.radius;
    if (best > reach)
      throw Error(key.at("deposit[" + std::to_string(k) + "].x") + ": the deposit at " +
                  point_text(deposit.x, deposit.y) + " is " + show(best) + " from the nearest mesh point " +
                  std::to_string(nearest) + " " + point_text(mesh.x[nearest], mesh.y[nearest]) +
                  ", more than the zones there are wide (" + show(width) + ")" +
                  (deposit.radius > 0 ? " plus 3 radii" : "") +
                  ": it lies outside the mesh and its energy would go into the zones nearest to it; check its "
                  "coordinates (and their units)");
  }
}

// The earliest lighting time of each burning material's zones (as the set-up computes it,
// time_offset + distance / D): after time.end nothing burns.
void warn_unlit_burns(const Problem& problem, const std::vector<ZoneState>& states,
                      const std::function<void(const std::string&, const std::string&)>& warn) {
  const Mesh& mesh = problem.mesh;
  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    if (!problem.materials[m].burn) continue;
    const Burn& burn = *problem.materials[m].burn;
    double earliest = std::numeric_limits<double>::infinity();
    for (Index z = 0; z < mesh.num_zones(); ++z) {
      if (states[z].material != static_cast<int>(m)) continue;
      const double cx = states[z].centre_x, cy = states[z].centre_y;
      double distance = std::numeric_limits<double>::infinity();
      for (const auto& pt : burn.points) distance = std::min(distance, std::hypot(cx - pt[0], cy - pt[1]));
      if (burn.plane) {
        const auto& pl = *burn.plane;
        distance = std::min(distance, std::abs((cx - pl[0]) * pl[2] + (cy - pl[1]) * pl[3]) / std::hypot(pl[2], pl[3]));
      }
      earliest = std::min(earliest, burn.time_offset + distance / burn.detonation_speed);
    }
    if (!(earliest > problem.t_end)) continue;  // also: no zone of the material
    const std::string path = "material[" + std::to_string(m) + "].burn.";
    warn(path + (burn.time_offset >= problem.t_end ? "time_offset" : "detonation_speed"),
         "no zone of material '" + problem.materials[m].name + "' lights before time.end = " + show(problem.t_end) +
             " (the first at t = " + show(earliest) + " = time_offset " + show(burn.time_offset) +
             " + distance / detonation_speed " + show(burn.detonation_speed) +
             "): nothing will burn; check time_offset, the detonation points and the units of the speed");
  }
}

// The unit system a scene states in scene.units, by its words: "Mbar" (cm, g, us, Mbar) or
// "SI" / "kg" / "Pa" (m, kg, s, Pa); anything else (dimensionless, none) is not checked.
struct UnitSystem {
  std::string text;  // scene.units as written
  double density_lo = 0, density_hi = 0, speed_lo = 0, speed_hi = 0, pressure_lo = 0, pressure_hi = 0;
  const char *density = "", *speed = "", *pressure = "", *slip = "";
};

std::optional<UnitSystem> stated_units(const toml::table& document) {
  const std::optional<std::string> text = document["scene"]["units"].value<std::string>();
  if (!text) return std::nullopt;
  bool si = false, mbar = false;
  std::string word;
  for (const char c : *text + " ") {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      continue;
    }
    si = si || word == "si" || word == "kg" || word == "pa";
    mbar = mbar || word == "mbar";
    word.clear();
  }
  // Condensed matter: densities 0.05 to 50 g/cm^3, sound speeds 0.01 to 2 cm/us, moduli and
  // JWL constants 1e-6 to 100 Mbar (a decade or more beyond real materials each way).
  if (mbar) return UnitSystem{*text, 0.05, 50, 0.01, 2, 1e-6, 100, "g/cm^3", "cm/us", "Mbar", "SI"};
  if (si) return UnitSystem{*text, 50, 5e4, 100, 2e4, 1e5, 1e13, "kg/m^3", "m/s", "Pa", "g/cm^3, cm/us or Mbar"};
  return std::nullopt;
}

// Densities and EOS constants implausible for the scene's stated units (JWL A and B in Pa in a
// Mbar scene, a density in g/cm^3 in an SI scene), and, whatever the units, a JWL A far from
// rho0 D^2 of its burn and a region's density far from its material's rho0.
void warn_implausible_units(const toml::table& document, const Problem& problem, const std::vector<ZoneState>& states,
                            const std::function<void(const std::string&, const std::string&)>& warn) {
  const std::optional<UnitSystem> units = stated_units(document);
  const auto check = [&](const std::string& path, double value, double lo, double hi, const char* unit,
                         const char* what) {
    if (!units || (value >= lo && value <= hi)) return;
    warn(path, show(value) + " is implausible for " + what + " in the scene's units (scene.units = \"" + units->text +
                   "\": " + show(lo) + " to " + show(hi) + " " + unit + "); check its units (a value in " +
                   units->slip + "?)");
  };
  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    const Material& material = problem.materials[m];
    const std::string path = "material[" + std::to_string(m) + "].";
    double rho0 = 0;
    if (const auto* mg = std::get_if<MieGruneisen>(&material.eos)) {
      rho0 = mg->rho0;
      if (units) check(path + "a0", mg->a0, units->speed_lo, units->speed_hi, units->speed, "a sound speed");
    } else if (const auto* jwl = std::get_if<Jwl>(&material.eos)) {
      rho0 = jwl->rho0;
      if (units) {
        check(path + "A", jwl->A, units->pressure_lo, units->pressure_hi, units->pressure, "a JWL constant");
        check(path + "B", jwl->B, units->pressure_lo, units->pressure_hi, units->pressure, "a JWL constant");
      }
      if (material.burn) {
        const double scale = jwl->rho0 * material.burn->detonation_speed * material.burn->detonation_speed;
        const double ratio = jwl->A / scale;
        if (!(ratio >= 0.1 && ratio <= 1000))
          warn(path + "A", show(jwl->A) + " is " + show(ratio) + " times rho0 D^2 = " + show(scale) +
                               " of its burn (real explosives: 1 to 100): A, rho0 and detonation_speed are in "
                               "different units");
      }
    } else if (const auto* sg = std::get_if<StiffenedGas>(&material.eos)) {
      if (units && sg->p_inf > 0)
        check(path + "p_inf", sg->p_inf, units->pressure_lo, units->pressure_hi, units->pressure, "a pressure");
    }
    if (units && rho0 > 0)
      check(path + "rho0", rho0, units->density_lo, units->density_hi, units->density,
            "the density of a condensed material");
    if (units && material.strength) {
      const double mu = shear_modulus(*material.strength, {});
      if (mu > 0)
        check(path + "strength.shear_modulus", mu, units->pressure_lo, units->pressure_hi, units->pressure,
              "a shear modulus");
    }
    // A region's density against its material's reference density (the first zone's).
    for (std::size_t r = 0; r < problem.regions.size() && rho0 > 0; ++r) {
      const auto first = std::find_if(states.begin(), states.end(), [&](const ZoneState& s) {
        return s.region == static_cast<int>(r) && s.material == static_cast<int>(m);
      });
      if (first == states.end() || (first->rho >= 0.1 * rho0 && first->rho <= 10 * rho0)) continue;
      warn("region[" + std::to_string(r) + "].density",
           show(first->rho) + " at " + point_text(first->centre_x, first->centre_y) + " is " + show(first->rho / rho0) +
               " times the rho0 = " + show(rho0) + " of material '" + material.name +
               "': the two are in different units");
    }
  }
}

}  // namespace

void check_boundary_geometry(const toml::table& document, const Scene& scene) {
  if (const auto wrong = boundary_geometry_problem(scene.problem))
    throw Error(
        Locator(document, scene.file).at(boundary_key(document, scene.problem.boundaries[wrong->boundary].tag)) + ": " +
        wrong->message);
}

void review_scene(const toml::table& document, Scene& scene, const WarningThresholds& limits) {
  const Problem& problem = scene.problem;
  const RunControl& control = scene.control;
  const HydroOptions& options = problem.options;
  const Locator key(document, scene.file);
  auto warn = [&](const std::string& path, const std::string& what) {
    scene.warnings.push_back(key.at(path) + ": " + what);
  };

  // The first time step, estimated as the set-up will take it: cfl * L / c over the zones
  // (no artificial viscosity yet, so the estimate is an upper bound), then dt_init, dt_max.
  const std::vector<ZoneState> states = initial_states(problem);
  // Unit slips first: an error below (a collapsing first step) is then likely theirs, and says so.
  std::vector<std::string> unit_warnings;
  warn_implausible_units(document, problem, states, [&](const std::string& path, const std::string& what) {
    unit_warnings.push_back(key.at(path) + ": " + what);
  });
  const auto failure = [&](const std::string& message) {
    return Error(unit_warnings.empty() ? message : message + " (note: " + unit_warnings.front() + ")");
  };
  for (const ZoneState& s : states)
    if (s.material >= 0 && !std::isfinite(s.c))
      throw failure(key.at("material[" + std::to_string(s.material) + "]") + ": the initial state at " +
                    point_text(s.centre_x, s.centre_y) + " (region '" + problem.regions[s.region].region +
                    "', density " + show(s.rho) +
                    ") has a non-finite sound speed; check the EOS constants and the "
                    "initial state");
  const double drive = driver_speed(problem, states);
  double cfl_length_over_c = std::numeric_limits<double>::infinity();   // min L / c
  double length_over_signal = std::numeric_limits<double>::infinity();  // min L / (c + |v| + drive)
  for (const ZoneState& s : states) {
    if (s.material < 0 || !(s.length > 0)) continue;
    if (s.c > 0) cfl_length_over_c = std::min(cfl_length_over_c, s.length / s.c);
    if (s.c + s.speed + drive > 0)
      length_over_signal = std::min(length_over_signal, s.length / (s.c + s.speed + drive));
  }
  const double t_end = problem.t_end;
  const double dt_min = options.dt_min > 0 ? options.dt_min : 1e-8 * t_end;
  const std::string dt_min_text =
      options.dt_min > 0 ? "numerics.dt_min = " + show(dt_min) : "dt_min = 1e-8 time.end = " + show(dt_min);
  if (options.dt_max > 0 && options.dt_max < dt_min)
    throw failure(key.at("numerics.dt_max") + ": " + show(options.dt_max) + " is below " + dt_min_text +
                  ": the first step would collapse; raise numerics.dt_max (or lower numerics.dt_min)");
  if (options.dt_init > 0 && options.dt_init < dt_min)
    throw failure(key.at("numerics.dt_init") + ": " + show(options.dt_init) + " is below " + dt_min_text +
                  ": the first step would collapse; raise numerics.dt_init (or lower numerics.dt_min)");
  if (std::isfinite(cfl_length_over_c)) {
    const double dt_cfl = options.cfl * cfl_length_over_c;
    if (dt_cfl < dt_min) {
      const std::string estimate = "the CFL time step at t = 0 (about " + show(dt_cfl) + ")";
      if (options.dt_min > 0)
        throw failure(key.at("numerics.dt_min") + ": " + show(dt_min) + " is above " + estimate +
                      ": the first step would collapse; lower numerics.dt_min");
      if (HydroOptions{}.cfl * cfl_length_over_c >= dt_min)
        throw failure(key.at("numerics.cfl") + ": " + show(options.cfl) + " puts " + estimate + " below " +
                      dt_min_text + ": the first step would collapse; use a cfl near the default " +
                      show(HydroOptions{}.cfl));
      throw failure(key.at("time.end") + ": " + show(t_end) + " is " +
                    (std::isfinite(t_end / dt_cfl) ? show(t_end / dt_cfl) : std::string("over 1e300")) + " times " +
                    estimate +
                    ", and the step may not fall below 1e-8 time.end: the run would stop at once; check the units of "
                    "time.end");
    }
  }

  // Dumps: refused above output.max_dumps (a tiny interval would fill the disk).
  const long dumps = estimated_dumps(control, problem.t_end);
  if (dumps > control.max_dumps)
    throw failure(key.at("output.dump_interval") + ": " + show(control.dump_interval) + " with time.end = " +
                  show(problem.t_end) + " gives " + show(std::floor(problem.t_end / control.dump_interval) + 2) +
                  " dumps, more than output.max_dumps = " + std::to_string(control.max_dumps) +
                  "; raise output.dump_interval (or output.max_dumps if you mean it)");

  check_deposits(problem, key);

  // Warnings from here on.
  warn_unlit_burns(problem, states, warn);
  scene.warnings.insert(scene.warnings.end(), unit_warnings.begin(), unit_warnings.end());
  // Few cycles: from the smallest plausible step (signal speed c + |v| + drivers), so the
  // count is an upper bound; many cycles: from the largest (c alone), a lower bound.
  auto capped = [&](double dt) { return options.dt_max > 0 ? std::min(dt, options.dt_max) : dt; };
  if (std::isfinite(length_over_signal)) {
    const double dt = capped(options.cfl * length_over_signal);
    const double cycles = t_end / dt;
    if (cycles < limits.min_cycles)
      warn("time.end", show(t_end) + " is about " + show(std::ceil(cycles)) + " time step(s) of ~" + show(dt) +
                           " (CFL on the state at t = 0): the run will last fewer than " + show(limits.min_cycles) +
                           " cycles; check the units of time.end");
  }
  if (std::isfinite(cfl_length_over_c) || options.dt_max > 0) {
    const double dt = capped(options.cfl * cfl_length_over_c);
    const double cycles = t_end / dt;
    if (cycles > limits.max_cycles)
      warn("time.end", show(t_end) + " is at least " + show(cycles) + " time steps of at most " + show(dt) +
                           " (CFL on the state at t = 0, numerics.dt_max): the run will take very long; check the "
                           "units of time.end");
  }

  // An option that weakens a check says so (docs/algorithm.md §9).
  if (!options.check_corner_areas)
    warn("numerics.check_corner_areas",
         "false weakens the tangling check: a zone whose median-mesh corner folds (a chevron) is accepted; "
         "zones with crossing edges or non-positive area are still refused");

  const Untagged untagged = untagged_boundary_edges(problem.mesh);
  if (untagged.count > 0) {
    std::string where;
    for (const auto& p : untagged.examples) where += (where.empty() ? "" : ", ") + point_text(p[0], p[1]);
    warn("mesh", std::to_string(untagged.count) + " boundary edge(s) have no tag and will be traction-free (e.g. at " +
                     where + "; all within x in [" + show(untagged.x0) + ", " + show(untagged.x1) + "], y in [" +
                     show(untagged.y0) + ", " + show(untagged.y1) +
                     "]); tag them (a Physical Curve) and give them a [[boundary]] (type = \"free\" if meant)");
  }

  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    const Material& material = problem.materials[m];
    if (!material.strength) continue;
    const std::string path = "material[" + std::to_string(m) + "].strength";
    // At t = 0: the model's mu and Y of the unstrained state.
    const double mu = shear_modulus(*material.strength, {}), yield = yield_stress(*material.strength, {});
    if (mu > 0 && yield > limits.yield_over_shear * mu)
      warn(path + ".yield_stress", show(yield) + " is " + show(yield / mu) + " times the shear modulus " + show(mu) +
                                       ": the material will never yield; check the units (e.g. Pa in a Mbar scene)");
    double bulk = 0;
    for (const ZoneState& s : states)
      if (s.material == static_cast<int>(m)) bulk = std::max(bulk, s.bulk);
    if (mu > 0 && bulk > 0) {
      const double ratio = mu / bulk;
      if (ratio < limits.shear_over_bulk_low || ratio > limits.shear_over_bulk_high)
        warn(path + ".shear_modulus", show(mu) + " is " + show(ratio) + " times the bulk modulus rho c^2 = " +
                                          show(bulk) + " of the EOS at t = 0: check the units of the two");
    }
  }

  if (const toml::table* ale = document["ale"].as_table())
    for (const auto& [name, value] : *ale)
      if (const std::string why = dead_ale_key(problem.ale, ale->contains("mode"), std::string(name.str()));
          !why.empty())
        warn("ale." + std::string(name.str()), why);

  if (const VelocityConflict conflict = shared_point_velocities(problem); conflict.count > 0)
    warn("region[" + std::to_string(conflict.later_region) + "].velocity",
         std::to_string(conflict.count) + " point(s) shared with region '" +
             problem.regions[conflict.first_region].region + "' (region[" + std::to_string(conflict.first_region) +
             "]) get different initial velocities from the two (e.g. at " + point_text(conflict.x, conflict.y) +
             ", up to |dv| = " + show(conflict.difference) + "); the first [[region]] in the file wins there, so " +
             "the order of the blocks sets the initial momentum: give the regions one velocity on their interface " +
             "(or order the blocks as meant)");

  for (std::size_t r = 0; r < problem.regions.size(); ++r) {
    std::size_t count = 0;
    double worst = 0;
    const ZoneState* at = nullptr;
    for (const ZoneState& s : states) {
      if (s.region != static_cast<int>(r) || !(s.c > 0)) continue;  // a cold gas (c = 0) has no scale
      const double ratio = s.speed / s.c;
      if (ratio > limits.speed_over_sound) {
        ++count;
        if (ratio > worst) worst = ratio, at = &s;
      }
    }
    if (count > 0)
      warn("region[" + std::to_string(r) + "].velocity",
           "the initial speed is above " + show(limits.speed_over_sound) + " times the sound speed in " +
               std::to_string(count) + " zone(s) (up to " + show(worst) + " times: |v| = " + show(at->speed) +
               ", c = " + show(at->c) + " at " + point_text(at->centre_x, at->centre_y) +
               "); check the units of the velocity");
  }
}

}  // namespace stagger::scene_detail
