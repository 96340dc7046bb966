#pragma once
/// @file option_table.hpp
/// The plain option sets of a Problem and a RunControl as tables, one row per option: its
/// scene key, the struct member it sets, the admissible values, the unit and a one-line
/// meaning. The default of an option is its member's default initialiser (read from a
/// value-initialised struct), so it is written once. The scene reader reads and range-checks
/// through these rows, Problem::validate() and RunControl::validate() check the same ranges
/// for set-ups built in code, describe() echoes the values, and the option tables of
/// docs/scenes.md are generated from them (the `stagger-options` tool; a test holds the file
/// equal to the generated text).
#include <limits>
#include <string>
#include <vector>

#include "stagger/materials.hpp"
#include "stagger/problem.hpp"
#include "stagger/run.hpp"

namespace stagger {

/// How an option is written in a scene.
enum class OptionType {
  number,   ///< a finite real number
  integer,  ///< an integer
  flag,     ///< true or false
  choice,   ///< one of a list of names (an enum member; the names are in enum order)
};

/// The admissible values of a number or integer option: an interval whose ends may be open
/// and infinite. Non-finite values are never admissible.
struct OptionRange {
  double low = -std::numeric_limits<double>::infinity();  ///< -inf: no lower bound
  double high = std::numeric_limits<double>::infinity();  ///< +inf: no upper bound
  bool low_open = false, high_open = false;               ///< an open end excludes its bound
  /// True for a finite value inside the interval (false for NaN and infinities).
  bool contains(double value) const;
  /// "in (0, 1)", "> 0", ">= 1", "<= 2", "any finite value".
  std::string text() const;
};

/// One row of an option table for the option struct `Options`.
template <class Options>
struct Option {
  const char* key = "";  ///< the scene key within its section
  OptionType type = OptionType::number;
  double (*get)(const Options&) = nullptr;  ///< the member's value (flag 0/1, choice: enum value)
  void (*set)(Options&, double) = nullptr;  ///< sets the member (the value is admissible)
  OptionRange range;                        ///< number, integer
  double integer_max = 0;                   ///< integer: the largest value the member holds
  std::vector<const char*> choices;         ///< choice: the names, indexed by enum value
  bool required = false;                    ///< no default: a scene must give it
  const char* unit = "";                    ///< "-" for a pure number, else a unit or quantity
  const char* doc = "";                     ///< one line: what it does

  /// The option's default: the value of a value-initialised Options.
  double default_value() const { return get(Options{}); }
  /// The value as a scene writes it: 0.15, 3, true, "bulk".
  std::string value_text(double value) const;
  /// Empty if `value` is admissible, else what is wrong: "must be in (0, 1), got 1.5".
  std::string check(double value) const;
  /// The admissible values in words: "(0, 1)", ">= 0", `"bulk"` or `"edge"`, true or false.
  std::string range_text() const;
};

/// The rows of one option set and where a scene keeps it.
template <class Options>
struct OptionTable {
  const char* section = "";      ///< scene section ("numerics"; "material.strength")
  const char* struct_name = "";  ///< the C++ struct ("HydroOptions")
  std::vector<Option<Options>> options;

  /// Throws stagger::Error "`where`key: must be ..., got ...; doc" for the first option of
  /// `values` that is not admissible (`where` defaults to "section.").
  void validate(const Options& values, const std::string& where = {}) const;
  /// "key = value" for every option, joined by ", " (describe()).
  std::string echo(const Options& values) const;
  /// The docs/scenes.md table: key, type, default, admissible values, unit, meaning.
  std::string markdown() const;
};

/// [numerics]: HydroOptions.
const OptionTable<HydroOptions>& numerics_option_table();
/// [ale]: AleOptions.
const OptionTable<AleOptions>& ale_option_table();
/// [time]: the end time of a Problem.
const OptionTable<Problem>& time_option_table();
/// [output]: the scene-settable part of RunControl (the directory, name, progress line and
/// reference are set by the scene's name, the CLI and [verification]).
const OptionTable<RunControl>& output_option_table();
/// [[deposit]]: EnergyDeposit.
const OptionTable<EnergyDeposit>& deposit_option_table();
/// [material.strength] of the linear-hardening model (`model = "linear_hardening"` or none):
/// LinearHardening (alias Strength). Defined with the model, lib/src/strength/linear_hardening.cpp.
const OptionTable<LinearHardening>& strength_option_table();
/// Every strength model's table as stagger-options prints it: "### [section] (Struct)", the
/// markdown table and a blank line, in the order of StrengthModel's alternatives.
std::string strength_option_tables_listing();
/// [[material]] with eos = "ideal_gas": IdealGas (section "ideal_gas").
const OptionTable<IdealGas>& ideal_gas_option_table();
/// [[material]] with eos = "mie_gruneisen": MieGruneisen (section "mie_gruneisen").
const OptionTable<MieGruneisen>& mie_gruneisen_option_table();
/// [[material]] with eos = "jwl": Jwl (section "jwl").
const OptionTable<Jwl>& jwl_option_table();
/// [[material]] with eos = "stiffened_gas": StiffenedGas (section "stiffened_gas").
const OptionTable<StiffenedGas>& stiffened_gas_option_table();

/// `document` with every generated block replaced by the current table: a block is the text
/// between a line `<!-- begin generated: SECTION options -->` and the next line
/// `<!-- end generated: SECTION options -->`, SECTION the section of one of the tables
/// above. Throws stagger::Error for an unknown SECTION, a block without its end, or a table
/// that has no block.
std::string with_generated_option_tables(const std::string& document);

}  // namespace stagger
