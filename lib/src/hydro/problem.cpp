// Problem validation: every name resolved, every number in range, before any array is built.
#include "stagger/problem.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "hydro/boundary_checks.hpp"
#include "stagger/error.hpp"
#include "stagger/option_table.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

SpaceFunction constant_field(double value) {
  return [value](double, double) { return value; };
}

TimeFunction constant_in_time(double value) {
  return [value](double) { return value; };
}

namespace {

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + ("'" + n + "'");
  return out.empty() ? "(none)" : out;
}

void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

void validate_material(const Material& m) {
  const std::string where = "material '" + m.name + "': ";
  require(!m.name.empty(), "a material has no name");
  if (const auto* g = std::get_if<IdealGas>(&m.eos)) ideal_gas_option_table().validate(*g, where);
  if (const auto* mg = std::get_if<MieGruneisen>(&m.eos)) mie_gruneisen_option_table().validate(*mg, where);
  if (const auto* j = std::get_if<Jwl>(&m.eos)) jwl_option_table().validate(*j, where);
  if (const auto* sg = std::get_if<StiffenedGas>(&m.eos)) stiffened_gas_option_table().validate(*sg, where);
  if (m.strength) validate_strength_model(*m.strength, where + "strength.");
  if (m.burn) {
    require(m.burn->detonation_speed > 0 && std::isnormal(m.burn->detonation_speed),
            where + "burn detonation_speed must be > 0 and a normal number (not denormal)");
    require(!m.burn->points.empty() || m.burn->plane.has_value(),
            where + "burn needs detonation points or a detonation plane");
    require(std::holds_alternative<Jwl>(m.eos), where + "burn needs a JWL equation of state");
  }
}

}  // namespace

void Problem::validate() const {
  require(mesh.num_zones() > 0, "problem '" + name + "': the mesh has no zones");
  // The ranges of the option tables (option_table.hpp), the same that the scene reader checks.
  time_option_table().validate(*this, "problem '" + name + "': time.");
  numerics_option_table().validate(options);
  ale_option_table().validate(ale);
  for (std::size_t k = 0; k < deposits.size(); ++k)
    deposit_option_table().validate(deposits[k], "deposit[" + std::to_string(k) + "].");
  if (options.geometry == CoordinateSystem::rz) {
    // Not derived for the area-weighted rz scheme (docs/algorithm.md §19).
    require(!(sources && sources->momentum),
            "problem '" + name + "': numerics.geometry = \"rz\" does not support a momentum source");
  }

  std::set<std::string> material_names;
  for (const auto& m : materials) {
    validate_material(m);
    require(material_names.insert(m.name).second, "material '" + m.name + "' is defined twice");
  }
  std::vector<std::string> all_materials(material_names.begin(), material_names.end());

  std::set<std::string> covered;
  for (const auto& r : regions) {
    require(mesh.region_index(r.region) >= 0, "region '" + r.region + "' is not in the mesh " + mesh.source +
                                                  " (its regions: " + list_names(mesh.region_names) + ")");
    require(material_names.count(r.material) > 0, "region '" + r.region + "': unknown material '" + r.material +
                                                      "' (defined: " + list_names(all_materials) + ")");
    require(covered.insert(r.region).second, "region '" + r.region + "' is set up twice");
    require(static_cast<bool>(r.density), "region '" + r.region + "': no density given");
    require(static_cast<bool>(r.pressure) != static_cast<bool>(r.specific_internal_energy),
            "region '" + r.region + "': give exactly one of pressure and specific_internal_energy");
  }
  for (const auto& name : mesh.region_names) {
    require(covered.count(name) > 0,
            "mesh region '" + name + "' of " + mesh.source + " has no material: add a region set-up for it");
  }
  for (const auto& b : boundaries) {
    require(
        mesh.tag_index(b.tag) >= 0, "boundary tag '" + b.tag + "' is not in the mesh " + mesh.source + " (its tags: " +
                                        [&] {
                                          std::vector<std::string> t;
                                          for (const auto& tag : mesh.tags) t.push_back(tag.name);
                                          return list_names(t);
                                        }() +
                                        ")");
    if (b.kind == BoundaryKind::periodic) {
      require(mesh.tag_index(b.partner) >= 0,
              "periodic boundary '" + b.tag + "': partner tag '" + b.partner + "' is not in the mesh");
    }
  }
  if (const auto wrong = boundary_geometry_problem(*this)) throw Error(wrong->message);
}

}  // namespace stagger
