// The option tables (option_table.hpp): one row per option, defaults from the structs'
// default member initialisers. Scene reading lives in lib/src/scene/option_reader.cpp.
#include "stagger/option_table.hpp"

#include <climits>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "stagger/error.hpp"

namespace stagger {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A number for messages and docs: 10 significant digits, like the scene reader's show().
std::string number_text(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// ---- rows from pointers to members ----

template <class Member>
struct MemberTraits;
template <class Object, class Value>
struct MemberTraits<Value Object::*> {
  using object = Object;
  using value = Value;
};
template <auto Member>
using ObjectOf = typename MemberTraits<decltype(Member)>::object;
template <auto Member>
using ValueOf = typename MemberTraits<decltype(Member)>::value;

template <auto Member>
double get_member(const ObjectOf<Member>& object) {
  if constexpr (std::is_enum_v<ValueOf<Member>>)
    return static_cast<double>(static_cast<int>(object.*Member));
  else
    return static_cast<double>(object.*Member);
}

template <auto Member>
void set_member(ObjectOf<Member>& object, double value) {
  using Value = ValueOf<Member>;
  if constexpr (std::is_enum_v<Value>)
    object.*Member = static_cast<Value>(static_cast<int>(value));
  else if constexpr (std::is_same_v<Value, bool>)
    object.*Member = value != 0;
  else
    object.*Member = static_cast<Value>(value);
}

template <auto Member>
Option<ObjectOf<Member>> row(const char* key, OptionType type, const char* unit, const char* doc) {
  Option<ObjectOf<Member>> option;
  option.key = key;
  option.type = type;
  option.get = &get_member<Member>;
  option.set = &set_member<Member>;
  option.unit = unit;
  option.doc = doc;
  return option;
}

OptionRange at_least(double low) {
  return {low, kInfinity, false, true};
}
OptionRange above(double low) {
  return {low, kInfinity, true, true};
}
const OptionRange kAnyValue{};

template <auto Member>
Option<ObjectOf<Member>> number(const char* key, OptionRange range, const char* unit, const char* doc) {
  static_assert(std::is_same_v<ValueOf<Member>, double>);
  auto option = row<Member>(key, OptionType::number, unit, doc);
  option.range = range;
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> required_number(const char* key, OptionRange range, const char* unit, const char* doc) {
  auto option = number<Member>(key, range, unit, doc);
  option.required = true;
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> integer(const char* key, OptionRange range, const char* unit, const char* doc) {
  using Value = ValueOf<Member>;
  static_assert(std::is_integral_v<Value> && !std::is_same_v<Value, bool>);
  auto option = row<Member>(key, OptionType::integer, unit, doc);
  option.range = range;
  option.integer_max = static_cast<double>(std::numeric_limits<Value>::max());
  return option;
}

template <auto Member>
Option<ObjectOf<Member>> flag(const char* key, const char* doc) {
  static_assert(std::is_same_v<ValueOf<Member>, bool>);
  return row<Member>(key, OptionType::flag, "-", doc);
}

template <auto Member>
Option<ObjectOf<Member>> choice(const char* key, std::vector<const char*> names, const char* doc) {
  static_assert(std::is_enum_v<ValueOf<Member>>);
  auto option = row<Member>(key, OptionType::choice, "-", doc);
  option.choices = std::move(names);
  return option;
}

template <class Options>
const Option<Options>* find_row(const OptionTable<Options>& table, const std::string& key) {
  for (const auto& option : table.options)
    if (key == option.key) return &option;
  return nullptr;
}

}  // namespace

// ---- OptionRange ----

bool OptionRange::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above_low = low_open ? value > low : value >= low;
  const bool below_high = high_open ? value < high : value <= high;
  return above_low && below_high;
}

std::string OptionRange::text() const {
  const bool has_low = std::isfinite(low), has_high = std::isfinite(high);
  if (has_low && has_high)
    return std::string("in ") + (low_open ? "(" : "[") + number_text(low) + ", " + number_text(high) +
           (high_open ? ")" : "]");
  if (has_low) return (low_open ? "> " : ">= ") + number_text(low);
  if (has_high) return (high_open ? "< " : "<= ") + number_text(high);
  return "any finite value";
}

// ---- Option ----

template <class Options>
std::string Option<Options>::value_text(double value) const {
  switch (type) {
    case OptionType::flag:
      return value != 0 ? "true" : "false";
    case OptionType::choice: {
      const auto index = static_cast<std::size_t>(value);
      return value >= 0 && index < choices.size() ? std::string("\"") + choices[index] + "\"" : number_text(value);
    }
    case OptionType::integer: {
      std::ostringstream out;
      out << static_cast<long long>(value);
      return out.str();
    }
    case OptionType::number:
      break;
  }
  return number_text(value);
}

template <class Options>
std::string Option<Options>::check(double value) const {
  switch (type) {
    case OptionType::flag:
      return {};
    case OptionType::choice:
      if (value >= 0 && static_cast<std::size_t>(value) < choices.size()) return {};
      return "must be one of " + range_text() + ", got " + number_text(value);
    case OptionType::integer:
      if (range.contains(value) && value > integer_max)
        return "must be at most " + value_text(integer_max) + ", got " + number_text(value);
      [[fallthrough]];
    case OptionType::number:
      if (!range.contains(value)) return "must be " + range.text() + ", got " + number_text(value);
      return {};
  }
  return {};
}

template <class Options>
std::string Option<Options>::range_text() const {
  switch (type) {
    case OptionType::flag:
      return "true or false";
    case OptionType::choice: {
      std::string text;
      for (std::size_t k = 0; k < choices.size(); ++k)
        text += std::string(k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + "\"" + choices[k] + "\"";
      return text;
    }
    case OptionType::integer:
    case OptionType::number: {
      const std::string text = range.text();
      return text.rfind("in ", 0) == 0 ? text.substr(3) : text;
    }
  }
  return {};
}

// ---- OptionTable ----

template <class Options>
void OptionTable<Options>::validate(const Options& values, const std::string& where) const {
  for (const auto& option : options) {
    const std::string problem = option.check(option.get(values));
    if (!problem.empty())
      throw Error((where.empty() ? std::string(section) + "." : where) + option.key + ": " + problem + "; " +
                  option.doc);
  }
}

template <class Options>
std::string OptionTable<Options>::echo(const Options& values) const {
  std::string text;
  for (const auto& option : options)
    text += (text.empty() ? "" : ", ") + std::string(option.key) + " = " + option.value_text(option.get(values));
  return text;
}

template <class Options>
std::string OptionTable<Options>::markdown() const {
  std::string text = "| key | type | default | admissible values | unit | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& option : options) {
    const char* type = option.type == OptionType::number    ? "number"
                       : option.type == OptionType::integer ? "integer"
                       : option.type == OptionType::flag    ? "bool"
                                                            : "string";
    text += "| `" + std::string(option.key) + "` | " + type + " | " +
            (option.required ? std::string("required") : "`" + option.value_text(option.default_value()) + "`") +
            " | " + option.range_text() + " | " + option.unit + " | " + option.doc + " |\n";
  }
  return text;
}

template struct Option<HydroOptions>;
template struct Option<AleOptions>;
template struct OptionTable<AleOptions>;
template struct Option<Problem>;
template struct Option<RunControl>;
template struct Option<EnergyDeposit>;
template struct Option<Strength>;
template struct OptionTable<HydroOptions>;
template struct OptionTable<Problem>;
template struct OptionTable<RunControl>;
template struct OptionTable<EnergyDeposit>;
template struct OptionTable<Strength>;
template struct Option<IdealGas>;
template struct Option<MieGruneisen>;
template struct Option<Jwl>;
template struct OptionTable<IdealGas>;
template struct OptionTable<MieGruneisen>;
template struct OptionTable<Jwl>;

// ---- the tables ----

const OptionTable<HydroOptions>& numerics_option_table() {
  using O = HydroOptions;
  static const OptionTable<HydroOptions> table{
      "numerics",
      "HydroOptions",
      {
          number<&O::cfl>("cfl", {0, 1, true, true}, "-", "Courant number c_t of the time-step limit (§9)"),
          choice<&O::viscosity>("viscosity", {"bulk", "edge", "tensor"},
                                "zone-centred bulk q (§4), edge viscosity with limiter (§5) or tensor q from "
                                "corner strain rates (§4.1)"),
          number<&O::q1>("q1", at_least(0), "-", "bulk and tensor q, quadratic coefficient (§4, §4.1)"),
          number<&O::q2>("q2", at_least(0), "-", "bulk and tensor q, linear coefficient (§4, §4.1)"),
          number<&O::edge_c1>("edge_c1", at_least(0), "-", "edge viscosity, linear coefficient c1 (§5)"),
          number<&O::edge_c2>("edge_c2", at_least(0), "-", "edge viscosity, quadratic coefficient c2 (§5)"),
          flag<&O::edge_limiter>("edge_limiter", "Christensen limiter of the edge viscosity (§5)"),
          choice<&O::hourglass>("hourglass", {"gamma", "flanagan_belytschko", "subzonal", "subzonal_triangles"},
                                "hourglass control: the paper's Gamma, Flanagan-Belytschko (§6), or subzonal "
                                "pressures on corners or side triangles (§18)"),
          number<&O::hourglass_coefficient>("hourglass_coefficient", at_least(0), "-",
                                            "hourglass coefficient Q (subzonal: merit factor); 0 turns it off"),
          choice<&O::stress_update>("stress_update", {"rate", "objective"},
                                    "deviatoric stress update: rate form or objective Hughes-Winget (§7)"),
          flag<&O::fresh_predictor>("fresh_predictor", "evaluate the predictor forces f^n afresh each cycle (§1)"),
          flag<&O::compensated_update>("compensated_update",
                                       "compensated (two-sum) accumulation of the point positions and velocities: "
                                       "no round-off drift over many cycles (§20)"),
          number<&O::volume_limit>("volume_limit", {0, 1, true, false}, "-",
                                   "f_A: largest relative area change per step (§9)"),
          number<&O::dt_growth>("dt_growth", at_least(1), "-", "largest growth of dt from one step to the next (§9)"),
          number<&O::dt_init>("dt_init", at_least(0), "time",
                              "first dt, if below the CFL value; 0: the CFL value (§9)"),
          number<&O::dt_max>("dt_max", at_least(0), "time", "largest dt; 0: none (§9)"),
          number<&O::dt_min>("dt_min", at_least(0), "time", "the run stops when dt falls below it; 0: 1e-8 t_end (§9)"),
          integer<&O::max_retries>("max_retries", {0, 30, false, false}, "-",
                                   "halvings of dt for a step that tangles the mesh (§9)"),
          flag<&O::check_corner_areas>("check_corner_areas",
                                       "a non-positive median-mesh corner area counts as tangling; false: zone "
                                       "areas only (a chevron zone passes; no shipped scene needs it, §9)"),
          choice<&O::geometry>("geometry", {"planar", "rz"},
                               "planar (x, y) per unit depth, or axisymmetric: x = r >= 0, y = z, masses and "
                               "energies per radian (§19)"),
          number<&O::heat_flux_c1>("heat_flux_c1", at_least(0), "-",
                                   "artificial heat flux, linear coefficient (with the sound speed; §21); 0 with "
                                   "heat_flux_c2 = 0: off"),
          number<&O::heat_flux_c2>("heat_flux_c2", at_least(0), "-",
                                   "artificial heat flux, quadratic coefficient (with l max(-div u, 0): in "
                                   "compression; §21)"),
      }};
  return table;
}

const OptionTable<AleOptions>& ale_option_table() {
  using A = AleOptions;
  static const OptionTable<AleOptions> table{
      "ale",
      "AleOptions",
      {
          choice<&A::mode>("mode", {"lagrangian", "ale", "eulerian"},
                           "mesh motion: with the material, rezoned and remapped, or back to the initial mesh "
                           "after every step (docs/ale.md)"),
          choice<&A::rezone>("rezone", {"winslow", "reference_jacobian", "winslow_regular"},
                             "rezone of mode \"ale\": Winslow smoothing with the initial mesh as logical space, "
                             "towards the initial zone shapes, or Winslow with regular local layouts"),
          number<&A::relaxation>("relaxation", {0, 1, false, false}, "-",
                                 "rezone: how far from the Lagrangian towards the smoothed mesh; 0: Lagrangian"),
          integer<&A::rezone_iterations>("rezone_iterations", {0, 1000, false, false}, "-",
                                         "rezone: smoothing sweeps per remap"),
          number<&A::corner_angle>("corner_angle", {0, 90, false, true}, "degrees",
                                   "rezone: boundary points slide only where the boundary turns by less"),
          number<&A::max_move>("max_move", {0, 1, true, false}, "-",
                               "rezone: largest move of a point per remap, in units of its shortest edge"),
          number<&A::size_weight>("size_weight", {0, 100, false, false}, "-",
                                  "rezone \"reference_jacobian\": weight of a term that pulls each zone's area, "
                                  "relative to its initial area, toward its neighbours'; 0: shapes only"),
          integer<&A::remap_every>("remap_every", {0, 1e9, false, false}, "cycles",
                                   "also remap after every N-th cycle; 0: off (remap only on the quality trigger)"),
          number<&A::quality_trigger>("quality_trigger", {0, 1, false, true}, "-",
                                      "remap after any cycle that leaves the worst zone shape quality (1 at t = 0) "
                                      "below it; 0: off"),
          choice<&A::limiter>("limiter", {"barth_jespersen", "none"},
                              "limiter of the remap's linear reconstruction (none: second order without bounds)"),
      }};
  return table;
}

const OptionTable<Problem>& time_option_table() {
  static const OptionTable<Problem> table{
      "time", "Problem", {required_number<&Problem::t_end>("end", above(0), "time", "end time")}};
  return table;
}

const OptionTable<RunControl>& output_option_table() {
  using R = RunControl;
  static const OptionTable<RunControl> table{
      "output",
      "RunControl",
      {
          number<&R::dump_interval>("dump_interval", at_least(0), "time",
                                    "time between .vtu dumps; 0: the first and the last only"),
          flag<&R::dumps>("dumps", "write .vtu/.pvd dumps (false: none, for benchmarks)"),
          integer<&R::max_dumps>("max_dumps", {1, 1e8, false, false}, "dumps",
                                 "most dumps a run may write (a tiny dump_interval would fill the disk)"),
          integer<&R::history_every>("history_every", at_least(1), "cycles", "a history.csv row every N cycles"),
          integer<&R::checkpoint_every_cycles>("checkpoint_every_cycles", at_least(0), "cycles",
                                               "a checkpoint every N cycles; 0: never by cycles"),
          number<&R::checkpoint_every_seconds>("checkpoint_every_seconds", at_least(0), "s (wall clock)",
                                               "a checkpoint every N seconds of wall-clock time; 0: never by time"),
          flag<&R::checkpoints>("checkpoints", "write checkpoints (false: none)"),
          flag<&R::gather_dumps>("gather_dumps",
                                 "a distributed run: gather each dump into one .vtu on rank 0 (the serial "
                                 "file) instead of a piece per rank and a .pvtu"),
      }};
  return table;
}

const OptionTable<EnergyDeposit>& deposit_option_table() {
  using D = EnergyDeposit;
  static const OptionTable<EnergyDeposit> table{
      "deposit",
      "EnergyDeposit",
      {
          required_number<&D::x>("x", kAnyValue, "length", "x of the point (radius 0: the nearest mesh point is used)"),
          required_number<&D::y>("y", kAnyValue, "length", "y of the point"),
          required_number<&D::energy>("energy", above(0), "energy per unit length in z",
                                      "internal energy put into the zones at t = 0 (where: see radius)"),
          number<&D::radius>("radius", at_least(0), "length",
                             "0: the zones around the nearest mesh point; > 0: a Gaussian of that radius in specific "
                             "energy, exp(-(d/radius)^2) at a zone centre's distance d from (x, y)"),
      }};
  return table;
}

const OptionTable<Strength>& strength_option_table() {
  using S = Strength;
  static const OptionTable<Strength> table{
      "material.strength",
      "Strength",
      {
          required_number<&S::shear_modulus>("shear_modulus", at_least(0), "pressure", "shear modulus mu (§7)"),
          required_number<&S::yield_stress>("yield_stress", above(0), "pressure",
                                            "von Mises yield stress Y (§7); a very large value gives an elastic "
                                            "material"),
          number<&S::hardening_modulus>("hardening_modulus", at_least(0), "pressure",
                                        "linear isotropic hardening H: the yield stress is Y + H eps_p with eps_p "
                                        "the equivalent plastic strain (§7); 0 is perfectly plastic"),
      }};
  return table;
}

const OptionTable<IdealGas>& ideal_gas_option_table() {
  static const OptionTable<IdealGas> table{
      "ideal_gas",
      "IdealGas",
      {required_number<&IdealGas::gamma>("gamma", above(1), "-", "ratio of specific heats; p = (gamma - 1) rho e")}};
  return table;
}

const OptionTable<MieGruneisen>& mie_gruneisen_option_table() {
  using M = MieGruneisen;
  static const OptionTable<MieGruneisen> table{
      "mie_gruneisen",
      "MieGruneisen",
      {
          required_number<&M::rho0>("rho0", above(0), "density", "reference density (§3)"),
          required_number<&M::a0>("a0", above(0), "velocity", "bulk sound speed, the Hugoniot's intercept c0 (§3)"),
          required_number<&M::gamma0>("gamma0", at_least(0), "-", "Grueneisen coefficient Gamma0 (§3)"),
          required_number<&M::s>("s", at_least(0), "-", "Hugoniot slope s, U_s = a0 + s u_p (§3)"),
      }};
  return table;
}

const OptionTable<Jwl>& jwl_option_table() {
  static const OptionTable<Jwl> table{
      "jwl",
      "Jwl",
      {
          required_number<&Jwl::A>("A", kAnyValue, "pressure", "first pressure coefficient (§3)"),
          required_number<&Jwl::B>("B", kAnyValue, "pressure", "second pressure coefficient (§3)"),
          required_number<&Jwl::R1>("R1", above(0), "-", "first decay constant (§3)"),
          required_number<&Jwl::R2>("R2", above(0), "-", "second decay constant (§3)"),
          required_number<&Jwl::omega>("omega", above(0), "-", "Grueneisen coefficient of the products (§3)"),
          required_number<&Jwl::rho0>("rho0", above(0), "density", "unreacted density; V = rho0 / rho (§3)"),
      }};
  return table;
}

// ---- validation of the run control ----

void RunControl::validate() const {
  output_option_table().validate(*this);
}

// ---- docs/scenes.md ----

namespace {

std::string generated_table(const std::string& section) {
  if (section == numerics_option_table().section) return numerics_option_table().markdown();
  if (section == time_option_table().section) return time_option_table().markdown();
  if (section == ale_option_table().section) return ale_option_table().markdown();
  if (section == output_option_table().section) return output_option_table().markdown();
  if (section == deposit_option_table().section) return deposit_option_table().markdown();
  if (section == strength_option_table().section) return strength_option_table().markdown();
  if (section == ideal_gas_option_table().section) return ideal_gas_option_table().markdown();
  if (section == mie_gruneisen_option_table().section) return mie_gruneisen_option_table().markdown();
  if (section == jwl_option_table().section) return jwl_option_table().markdown();
  throw Error("generated option table: unknown section '" + section +
              "' (known: numerics, time, output, deposit, material.strength, ideal_gas, mie_gruneisen, jwl, ale)");
}

}  // namespace

std::string with_generated_option_tables(const std::string& document) {
  static const std::string begin_mark = "<!-- begin generated: ", end_mark = "<!-- end generated: ",
                           close = " options -->";
  const std::vector<std::string> sections = {"numerics",  "time",          "output", "deposit", "material.strength",
                                             "ideal_gas", "mie_gruneisen", "jwl",    "ale"};
  std::vector<std::string> seen;
  std::istringstream in(document);
  std::string out, line;
  std::string open_section;  // inside a block: its section
  int line_number = 0, open_line = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const bool last_line_unterminated = in.eof();
    const auto ends_with_close = [&] {
      return line.size() >= close.size() && line.compare(line.size() - close.size(), close.size(), close) == 0;
    };
    if (open_section.empty()) {
      out += line;
      if (!last_line_unterminated) out += '\n';
      if (line.rfind(begin_mark, 0) == 0 && ends_with_close()) {
        open_section = line.substr(begin_mark.size(), line.size() - begin_mark.size() - close.size());
        open_line = line_number;
        out += generated_table(open_section);
        seen.push_back(open_section);
      }
    } else if (line.rfind(end_mark, 0) == 0 && ends_with_close()) {
      const std::string section = line.substr(end_mark.size(), line.size() - end_mark.size() - close.size());
      if (section != open_section)
        throw Error("line " + std::to_string(line_number) + ": '" + line + "' closes a block opened for '" +
                    open_section + "' at line " + std::to_string(open_line));
      out += line;
      if (!last_line_unterminated) out += '\n';
      open_section.clear();
    }
    // Other lines inside a block are the old table: dropped.
  }
  if (!open_section.empty())
    throw Error("line " + std::to_string(open_line) + ": the generated block for '" + open_section +
                "' has no end line (" + end_mark + open_section + close + ")");
  for (const auto& section : sections) {
    bool found = false;
    for (const auto& s : seen) found = found || s == section;
    if (!found)
      throw Error("no generated block for the " + section + " options (" + begin_mark + section + close + " ... " +
                  end_mark + section + close + ")");
  }
  return out;
}

}  // namespace stagger
