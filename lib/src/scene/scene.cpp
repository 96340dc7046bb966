// Scene files (TOML) -> Problem + RunControl. The reader is a translation into the public
// API, nothing more: every value lands in a field of problem.hpp or run.hpp.
#include "stagger/scene.hpp"

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "io/atomic_file.hpp"
#include "option_table_reader.hpp"
#include "overrides.hpp"
#include "scene_internal.hpp"
#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"
#include "strength/strength_models.hpp"
#include "warnings.hpp"

namespace stagger {

namespace scene_detail {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "(none)" : list;
}

std::string point_text(double x, double y) {
  std::ostringstream out;
  out.precision(6);
  out << "(" << x << ", " << y << ")";
  return out.str();
}

// Checks a value at `points`; a non-finite value is an error naming the point.
void check_finite(Section& section, const Section::ValueOrExpression& value, const std::string& key_label,
                  const std::vector<std::array<double, 2>>& points,
                  const std::function<bool(double)>& in_range = nullptr, const std::string& range_text = {}) {
  for (const auto& point : points) {
    const double v = value.constant ? *value.constant : (*value.expression)(point[0], point[1]);
    if (!std::isfinite(v))
      section.fail_at(value.node, key_label, "evaluates to " + show(v) + " at " + point_text(point[0], point[1]),
                      "guard divisions and roots, e.g. with ?:");
    if (in_range && !in_range(v))
      section.fail_at(value.node, key_label,
                      "must be " + range_text + ", got " + show(v) + " at " + point_text(point[0], point[1]));
    if (value.constant) break;  // a constant needs one check
  }
}

// The initial state must lie in the EOS's domain at every zone centre, checked here (not
// only at set-up in the core) so that `stagger check` reports it with the file and key.
void check_eos_domain(Section& section, const Material& material, const Section::ValueOrExpression& density,
                      const Section::ValueOrExpression& thermal, bool has_pressure, const char* thermal_key,
                      const std::vector<std::array<double, 2>>& centres) {
  const auto value = [](const Section::ValueOrExpression& v, const std::array<double, 2>& at) {
    return v.constant ? *v.constant : (*v.expression)(at[0], at[1]);
  };
  for (const auto& centre : centres) {
    const double rho = value(density, centre), given = value(thermal, centre);
    if (const auto* mg = std::get_if<MieGruneisen>(&material.eos)) {
      // Paper eq. (6): the Hugoniot term has 1 - s eta in its denominator, eta = 1 - rho0/rho.
      const double eta = 1 - mg->rho0 / rho;
      if (!(1 - mg->s * eta > 0))
        section.fail_at(
            density.node, section.key_path("density"),
            "density " + show(rho) + " at " + point_text(centre[0], centre[1]) +
                " is outside the Mie-Gruneisen domain of material '" + material.name +
                "' (1 - s eta = " + show(1 - mg->s * eta) + " <= 0; rho must stay below rho0 s / (s - 1) = " +
                show(mg->s > 1 ? mg->rho0 * mg->s / (mg->s - 1) : std::numeric_limits<double>::infinity()) + ")",
            "lower the density or check rho0 and s");
    }
    std::string problem;
    try {
      const double e = has_pressure ? eos_energy_from_pressure(material.eos, rho, given) : given;
      if (!std::isfinite(e))
        problem = "gives a non-finite specific internal energy";
      else if (!(eos_sound_speed_squared(material.eos, rho, e) > 0) && !std::holds_alternative<IdealGas>(material.eos))
        problem = "gives a non-positive sound speed squared";
    } catch (const Error& failure) {
      problem = std::string("is outside the domain (") + failure.what() + ")";
    }
    if (!problem.empty())
      section.fail_at(thermal.node, section.key_path(thermal_key),
                      "the state rho = " + show(rho) + ", " + thermal_key + " = " + show(given) + " at " +
                          point_text(centre[0], centre[1]) + " " + problem + " of material '" + material.name + "' (" +
                          eos_kind(material.eos) + ")",
                      "check the initial state and the EOS constants");
  }
}

SpaceFunction to_space_function(const Section::ValueOrExpression& value) {
  return value.constant ? constant_field(*value.constant) : space_function(*value.expression);
}

TimeFunction to_time_function(const Section::ValueOrExpression& value) {
  return value.constant ? constant_in_time(*value.constant) : time_function(*value.expression);
}

void read_scene_section(Section& root, const std::string& file, Problem& problem, RunControl& control) {
  // The name becomes output file names: a safe set only (no path, no control characters).
  std::string name = safe_name(std::filesystem::path(file).stem().string());
  if (auto scene = root.subtable("scene")) {
    name = scene->string("name", name);
    if (const std::string reason = unsafe_name_reason(name); !reason.empty())
      scene->fail("name", "the name " + reason + "; it names the output files",
                  "use letters, digits, '_', '-' and '.' (not first, not '..'), at most " +
                      std::to_string(kMaxNameLength) + " characters");
    scene->string("description", "");
    scene->string("units", "");
    scene->finish();
  }
  problem.name = name;
  control.name = name;
  control.output_directory = "output/" + name;
}

Material read_material(Section& section) {
  Material material;
  material.name = section.string("name");
  const std::string eos = section.choice("eos", {"ideal_gas", "mie_gruneisen", "jwl", "stiffened_gas"});
  if (eos == "ideal_gas") {
    IdealGas gas;
    read_options(section, ideal_gas_option_table(), gas);
    material.eos = gas;
  } else if (eos == "mie_gruneisen") {
    MieGruneisen mg;
    read_options(section, mie_gruneisen_option_table(), mg);
    material.eos = mg;
  } else if (eos == "stiffened_gas") {
    StiffenedGas sg;
    read_options(section, stiffened_gas_option_table(), sg);
    material.eos = sg;
  } else {
    Jwl jwl;
    read_options(section, jwl_option_table(), jwl);
    material.eos = jwl;
  }
  if (section.has("min_energy")) material.min_energy = section.number("min_energy");
  if (auto strength = section.subtable("strength")) {
    StrengthModel model =
        default_strength_model(strength->choice("model", strength_model_names(), kDefaultStrengthModel));
    std::visit([&](auto& m) { read_options(*strength, strength_option_table_of(m), m); }, model);
    strength->finish();
    material.strength = model;
  }
  if (auto burn_section = section.subtable("burn")) {
    Burn burn;
    burn.detonation_speed = burn_section->number("detonation_speed");
    if (!(burn.detonation_speed > 0)) burn_section->fail("detonation_speed", "must be > 0");
    if (!std::isnormal(burn.detonation_speed))
      burn_section->fail("detonation_speed",
                         "must be a normal number, got the denormal " + show(burn.detonation_speed) +
                             ": the detonation would never travel",
                         "check the value and its units");
    if (const toml::node* points = burn_section->find("points")) {
      const auto* array = points->as_array();
      if (array == nullptr)
        burn_section->fail("points", "expected an array of [x, y] pairs", "write points = [[0.0, 0.0]]");
      for (const toml::node& element : *array) {
        const auto* pair = element.as_array();
        if (pair == nullptr || pair->size() != 2)
          burn_section->fail_at(&element, burn_section->key_path("points"), "each detonation point is [x, y]");
        const std::string label = burn_section->key_path("points") + "[" + std::to_string(burn.points.size()) + "]";
        burn.points.push_back({burn_section->number_at(*pair->get(0), label + "[0]"),
                               burn_section->number_at(*pair->get(1), label + "[1]")});
      }
    }
    if (burn_section->has("plane")) {
      const auto plane = burn_section->numbers("plane", 4);
      if (std::hypot(plane[2], plane[3]) == 0) burn_section->fail("plane", "the normal (nx, ny) is zero");
      burn.plane = std::array<double, 4>{plane[0], plane[1], plane[2], plane[3]};
    }
    if (burn.points.empty() && !burn.plane)
      burn_section->fail("points", "missing: a burn needs detonation points or a plane",
                         "write points = [[x, y]] or plane = [x0, y0, nx, ny]");
    burn.time_offset = burn_section->number("time_offset", 0.0);
    burn.beta_burn = burn_section->boolean("beta_burn", false);
    burn.cj_relative_volume = burn_section->number("cj_relative_volume", 0.0);
    if (burn.beta_burn && !(burn.cj_relative_volume > 0 && burn.cj_relative_volume < 1))
      burn_section->fail("cj_relative_volume", "beta_burn needs 0 < cj_relative_volume < 1");
    burn_section->finish();
    material.burn = burn;
  }
  section.finish();
  return material;
}

void read_regions(Section& root, const Mesh& mesh, Problem& problem) {
  std::map<std::string, std::size_t> material_index;
  std::vector<std::string> material_names;
  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    material_index[problem.materials[m].name] = m;
    material_names.push_back(problem.materials[m].name);
  }
  auto sections = root.table_array("region");
  if (sections.empty())
    root.fail("region", "missing: no [[region]]", "add one per mesh region: " + join(mesh.region_names));
  std::set<std::string> covered;
  const std::vector<std::string> xy{"x", "y"};
  for (auto& section : sections) {
    RegionSetup setup;
    setup.region = section.string("name");
    const int region = mesh.region_index(setup.region);
    if (region < 0)
      section.fail("name", "the mesh has no region '" + setup.region + "'", "mesh regions: " + join(mesh.region_names));
    if (!covered.insert(setup.region).second) section.fail("name", "region '" + setup.region + "' is set up twice");
    setup.material = section.string("material");
    const auto found = material_index.find(setup.material);
    if (found == material_index.end())
      section.fail("material", "unknown material '" + setup.material + "'", "materials: " + join(material_names));
    const Material& material = problem.materials[found->second];
    const bool ideal_gas = std::holds_alternative<IdealGas>(material.eos);

    std::vector<std::array<double, 2>> centres, points;
    std::set<Index> point_set;
    for (Index z = mesh.region_zone_begin[region]; z < mesh.region_zone_begin[region + 1]; ++z) {
      centres.push_back(zone_centre(mesh, z));
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c)
        point_set.insert(mesh.corner_point[c]);
    }
    for (Index p : point_set) points.push_back({mesh.x[p], mesh.y[p]});

    const auto density = section.value_or_expression("density", xy);
    check_finite(
        section, density, section.key_path("density"), centres, [](double v) { return v > 0; }, "> 0");
    setup.density = to_space_function(density);
    const bool has_pressure = section.has("pressure"), has_energy = section.has("specific_internal_energy");
    if (has_pressure == has_energy)
      section.fail(has_pressure ? "specific_internal_energy" : "pressure",
                   has_pressure ? "give pressure or specific_internal_energy, not both"
                                : "missing: give pressure or specific_internal_energy");
    const char* thermal_key = has_pressure ? "pressure" : "specific_internal_energy";
    const auto thermal = section.value_or_expression(thermal_key, xy);
    if (ideal_gas)
      check_finite(
          section, thermal, section.key_path(thermal_key), centres, [](double v) { return v >= 0; },
          ">= 0 for an ideal gas");
    else
      check_finite(section, thermal, section.key_path(thermal_key), centres);
    (has_pressure ? setup.pressure : setup.specific_internal_energy) = to_space_function(thermal);
    check_eos_domain(section, material, density, thermal, has_pressure, thermal_key, centres);

    if (const toml::node* velocity = section.find("velocity")) {
      const auto* array = velocity->as_array();
      if (array == nullptr || array->size() != 2)
        section.fail("velocity", "expected [vx, vy] (numbers or expressions of x, y)");
      const char* labels[2] = {"[0]", "[1]"};
      for (std::size_t k = 0; k < 2; ++k) {
        const std::string label = section.key_path("velocity") + labels[k];
        const auto component = section.value_or_expression(*array->get(k), label, xy);
        check_finite(section, component, label, points);
        (k == 0 ? setup.velocity_x : setup.velocity_y) = to_space_function(component);
      }
    }
    if (const toml::node* stress = section.find("stress")) {
      if (!material.strength)
        section.fail("stress", "material '" + material.name + "' has no [material.strength]",
                     "remove the stress or give the material a strength");
      const auto* array = stress->as_array();
      if (array == nullptr || array->size() != 3)
        section.fail("stress", "expected [sxx, syy, sxy] (numbers or expressions of x, y)");
      const char* labels[3] = {"[0]", "[1]", "[2]"};
      SpaceFunction* targets[3] = {&setup.stress_xx, &setup.stress_yy, &setup.stress_xy};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string label = section.key_path("stress") + labels[k];
        const auto component = section.value_or_expression(*array->get(k), label, xy);
        check_finite(section, component, label, centres);
        *targets[k] = to_space_function(component);
      }
    }
    section.finish();
    problem.regions.push_back(std::move(setup));
  }
  std::vector<std::string> uncovered;
  for (const auto& region : mesh.region_names)
    if (covered.count(region) == 0) uncovered.push_back(region);
  if (!uncovered.empty())
    root.fail("region", "mesh region(s) " + join(uncovered) + " have no [[region]]",
              "add a [[region]] with name, material and initial state for each");
}

void read_boundaries(Section& root, const Mesh& mesh, double t_end, Problem& problem) {
  std::vector<std::string> tag_names;
  for (const auto& tag : mesh.tags) tag_names.push_back(tag.name);
  std::map<std::string, std::string> covered;  // tag -> where it was set
  auto claim = [&](Section& section, const char* key, const std::string& tag) {
    if (mesh.tag_index(tag) < 0)
      section.fail(key, "the mesh has no boundary tag '" + tag + "'", "mesh tags: " + join(tag_names));
    if (!covered.emplace(tag, section.path()).second)
      section.fail(key, "tag '" + tag + "' already has a condition (" + covered[tag] + ")");
  };
  std::vector<double> sample_times;
  for (int i = 0; i <= 20; ++i) sample_times.push_back(t_end * i / 20.0);
  auto check_time = [&](Section& section, const Section::ValueOrExpression& value, const std::string& label) {
    if (value.constant) return;
    for (double t : sample_times)
      if (!std::isfinite((*value.expression)(t)))
        section.fail_at(value.node, label, "not finite at t = " + show(t), "guard the expression");
  };

  for (auto& section : root.table_array("boundary")) {
    std::vector<std::string> tags;
    const char* tag_key = "tags";
    if (section.has("tags") && section.has("tag")) section.fail("tag", "give tag or tags, not both");
    if (section.has("tag")) {
      tags.push_back(section.string("tag"));
      tag_key = "tag";
    } else {
      tags = section.strings("tags");
      if (tags.empty()) section.fail("tags", "lists no tag", "mesh tags: " + join(tag_names));
    }
    for (const auto& tag : tags) claim(section, tag_key, tag);
    BoundaryCondition condition;
    const std::string type =
        section.choice("type", {"wall", "velocity", "free", "pressure", "periodic", "fixed", "transmitting"});
    if (type == "wall") {
      condition.kind = BoundaryKind::wall;
    } else if (type == "fixed") {
      condition.kind = BoundaryKind::fixed;
    } else if (type == "transmitting") {
      condition.kind = BoundaryKind::transmitting;
      // The far-field pressure: given, or the adjacent zone's at t = 0 (docs/scenes.md).
      condition.far_field_from_initial_state = !section.has("pressure");
      if (section.has("pressure")) {
        const auto pressure = section.value_or_expression("pressure", {"t"});
        check_time(section, pressure, section.key_path("pressure"));
        condition.pressure = to_time_function(pressure);
      }
    } else if (type == "free") {
      condition.kind = BoundaryKind::free;
    } else if (type == "velocity") {
      condition.kind = BoundaryKind::velocity;
      const toml::node* velocity = section.find("velocity");
      const auto* array = velocity ? velocity->as_array() : nullptr;
      if (array == nullptr || array->size() != 2)
        section.fail("velocity", velocity ? "expected [ux, uy] (numbers or expressions of t)" : "missing",
                     "write velocity = [1.0, 0.0]");
      for (std::size_t k = 0; k < 2; ++k) {
        const std::string label = section.key_path("velocity") + (k == 0 ? "[0]" : "[1]");
        const auto component = section.value_or_expression(*array->get(k), label, {"t"});
        check_time(section, component, label);
        (k == 0 ? condition.velocity_x : condition.velocity_y) = to_time_function(component);
      }
    } else if (type == "pressure") {
      condition.kind = BoundaryKind::pressure;
      const auto pressure = section.value_or_expression("pressure", {"t"});
      check_time(section, pressure, section.key_path("pressure"));
      condition.pressure = to_time_function(pressure);
    } else {
      condition.kind = BoundaryKind::periodic;
      if (tags.size() != 1) section.fail(tag_key, "a periodic condition pairs one tag with its partner");
      condition.partner = section.string("partner");
      claim(section, "partner", condition.partner);
    }
    section.finish();
    for (const auto& tag : tags) {
      condition.tag = tag;
      problem.boundaries.push_back(condition);
    }
  }
  std::vector<std::string> uncovered;
  for (const auto& tag : tag_names)
    if (covered.count(tag) == 0) uncovered.push_back(tag);
  if (!uncovered.empty())
    root.fail("boundary", "mesh tag(s) " + join(uncovered) + " have no [[boundary]]",
              "add one (type = \"free\" for a traction-free surface)");
}

}  // namespace
}  // namespace scene_detail

namespace {

// load_scene, or with `outline` load_scene_without_mesh.
Scene read_scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides,
                 Mesh* outline) {
  using namespace scene_detail;
  if (const std::string problem = meshgen::file_problem(path); !problem.empty())
    throw Error(path + ": scene file " +
                (problem.rfind("not found", 0) == 0 ? problem : problem + ", not a regular file") + "; check the path");
  toml::table document;
  try {
    const std::string text = io_detail::read_file(path);
    if (const std::string deep = too_deep_line(text); !deep.empty())
      throw Error(path + ":" + deep.substr(5) + ": a key nests more than " + std::to_string(kMaxKeyDepth) +
                  " levels deep (dotted parts, table headers and inline tables); stagger reads no deeper scenes");
    document = toml::parse(text, path);
  } catch (const toml::parse_error& failure) {
    const auto& begin = failure.source().begin;
    throw Error(path + ":" + std::to_string(begin.line) + ":" + std::to_string(begin.column) +
                ": malformed TOML: " + std::string(failure.description()) + "; fix the syntax (see docs/scenes.md)");
  }
  for (const auto& [key, value] : overrides) apply_override(document, key, value);

  Scene scene;
  scene.file = path;
  Problem& problem = scene.problem;
  RunControl& control = scene.control;
  Section root(path, document, "");
  // Reject unknown top-level keys before the (possibly slow) meshing.
  for (const char* key : {"scene", "time", "mesh", "material", "region", "boundary", "deposit", "numerics", "output",
                          "sources", "verification", "ale"})
    root.find(key);
  root.finish();

  read_scene_section(root, path, problem, control);

  auto time = root.subtable("time");
  if (!time) root.fail("time", "missing: every scene needs [time] with end", "add [time] end = ...");
  read_options(*time, time_option_table(), problem);
  time->finish();

  auto mesh = root.subtable("mesh");
  if (!mesh) root.fail("mesh", "missing: every scene needs a [mesh]", "add [mesh] with file or generator");
  if (outline) {
    problem.mesh = std::move(*outline);
    problem.mesh.region_zone_begin.assign(problem.mesh.region_names.size() + 1, 0);
  } else {
    problem.mesh = read_mesh_section(*mesh, path, scene.notes);
  }

  auto materials = root.table_array("material");
  if (materials.empty()) root.fail("material", "missing: no [[material]]", "add one [[material]] per material");
  for (auto& section : materials) {
    Material material = read_material(section);
    for (const auto& other : problem.materials)
      if (other.name == material.name) section.fail("name", "material '" + material.name + "' is defined twice");
    problem.materials.push_back(std::move(material));
  }

  read_regions(root, problem.mesh, problem);
  read_boundaries(root, problem.mesh, problem.t_end, problem);

  for (auto& section : root.table_array("deposit")) {
    EnergyDeposit deposit;
    read_options(section, deposit_option_table(), deposit);
    section.finish();
    problem.deposits.push_back(deposit);
  }

  if (auto numerics = root.subtable("numerics")) {
    read_options(*numerics, numerics_option_table(), problem.options);
    numerics->finish();
  }
  if (auto ale = root.subtable("ale")) {
    read_options(*ale, ale_option_table(), problem.ale);
    ale->finish();
  }
  if (auto output = root.subtable("output")) {
    read_options(*output, output_option_table(), control);
    output->finish();
  }
  SourceContext source_context;
  if (auto sources = root.subtable("sources")) source_context = read_sources_section(*sources, problem);
  if (auto verification = root.subtable("verification"))
    read_verification_section(*verification, problem, source_context, control, scene.verification);
  root.finish();
  if (outline) return scene;  // no zones to validate or review: rank 0 did (docs/parallel.md)

  check_boundary_geometry(document, scene);
  try {
    problem.validate();
  } catch (const Error& failure) {
    throw Error(path + ": " + failure.what());
  }
  review_scene(document, scene);
  return scene;
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides) {
  return read_scene(path, overrides, nullptr);
}

Scene load_scene_without_mesh(const std::string& path,
                              const std::vector<std::pair<std::string, std::string>>& overrides, Mesh outline) {
  outline.zone_corner_begin.assign(1, 0);
  outline.point_corner_begin.assign(1, 0);
  outline.x.clear(), outline.y.clear(), outline.corner_point.clear(), outline.corner_zone.clear();
  outline.point_corners.clear(), outline.zone_region.clear();
  for (BoundaryTag& tag : outline.tags) tag.edges.clear(), tag.points.clear();
  return read_scene(path, overrides, &outline);
}

}  // namespace stagger
