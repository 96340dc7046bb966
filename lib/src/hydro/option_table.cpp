// The option tables (option_table.hpp): one row per option, defaults from the structs'
// default member initialisers. Scene reading lives in lib/src/scene/option_reader.cpp.
#include "stagger/option_table.hpp"

#include "hydro/option_rows.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

using namespace option_rows;

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

template struct Option<HydroOptions>;
template struct Option<AleOptions>;
template struct OptionTable<AleOptions>;
template struct Option<Problem>;
template struct Option<RunControl>;
template struct Option<EnergyDeposit>;
template struct OptionTable<HydroOptions>;
template struct OptionTable<Problem>;
template struct OptionTable<RunControl>;
template struct OptionTable<EnergyDeposit>;
template struct Option<IdealGas>;
template struct Option<MieGruneisen>;
template struct Option<Jwl>;
template struct Option<StiffenedGas>;
template struct OptionTable<IdealGas>;
template struct OptionTable<MieGruneisen>;
template struct OptionTable<Jwl>;
template struct OptionTable<StiffenedGas>;

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

const OptionTable<StiffenedGas>& stiffened_gas_option_table() {
  using G = StiffenedGas;
  static const OptionTable<StiffenedGas> table{
      "stiffened_gas",
      "StiffenedGas",
      {
          required_number<&G::gamma>("gamma", above(1), "-", "p = (gamma - 1) rho e - gamma p_inf (§3)"),
          required_number<&G::p_inf>("p_inf", at_least(0), "pressure", "stiffening pressure; 0: an ideal gas (§3)"),
      }};
  return table;
}

// ---- validation of the run control ----

void RunControl::validate() const {
  output_option_table().validate(*this);
}

// ---- docs/scenes.md ----

std::string strength_option_tables_listing() {
  std::string text;
  for (const StrengthTableText& table : strength_option_table_texts())
    text += "### [" + table.section + "] (" + table.struct_name + ")\n" + table.markdown + "\n";
  return text;
}

namespace {

std::string generated_table(const std::string& section) {
  if (section == numerics_option_table().section) return numerics_option_table().markdown();
  if (section == time_option_table().section) return time_option_table().markdown();
  if (section == ale_option_table().section) return ale_option_table().markdown();
  if (section == output_option_table().section) return output_option_table().markdown();
  if (section == deposit_option_table().section) return deposit_option_table().markdown();
  for (const StrengthTableText& table : strength_option_table_texts())
    if (section == table.section) return table.markdown;
  if (section == ideal_gas_option_table().section) return ideal_gas_option_table().markdown();
  if (section == mie_gruneisen_option_table().section) return mie_gruneisen_option_table().markdown();
  if (section == jwl_option_table().section) return jwl_option_table().markdown();
  if (section == stiffened_gas_option_table().section) return stiffened_gas_option_table().markdown();
  throw Error("generated option table: unknown section '" + section +
              "' (known: numerics, time, output, deposit, material.strength, ideal_gas, mie_gruneisen, jwl, "
              "stiffened_gas, ale)");
}

}  // namespace

std::string with_generated_option_tables(const std::string& document) {
  static const std::string begin_mark = "<!-- begin generated: ", end_mark = "<!-- end generated: ",
                           close = " options -->";
  std::vector<std::string> sections = {"numerics",      "time", "output",        "deposit", "ideal_gas",
                                       "mie_gruneisen", "jwl",  "stiffened_gas", "ale"};
  for (const StrengthTableText& table : strength_option_table_texts()) sections.push_back(table.section);
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
