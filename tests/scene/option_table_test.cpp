// The option tables (stagger/option_table.hpp): docs/scenes.md holds the generated tables,
// every row is wired to its own member, and the scene reader and the library's validate()
// accept and reject the same values.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include "stagger/error.hpp"
#include "stagger/option_table.hpp"
#include "stagger/scene.hpp"
#include "support/scene_toml.hpp"
#include "support/scratch_directory.hpp"

namespace fs = std::filesystem;

namespace {

namespace toml = stagger::testing::toml;

// Every kind of material (the gas with strength, so that its options are read too) and a deposit;
// the mesh holds the deposit's point moved by 1 (a deposit outside the mesh is refused).
const std::string small_scene = toml::time("0.1") + toml::rectangle("[0.0, 1.0]", "[0.0, 1.0]", 10, 2) +
                                toml::ideal_gas() + "[material.strength]\nshear_modulus = 2.0\nyield_stress = 3.0\n" +
                                toml::copper() + R"([[material]]
name = "explosive"
eos = "jwl"
A = 5.242
B = 0.07678
R1 = 4.2
R2 = 1.1
omega = 0.34
rho0 = 1.712
)" + toml::gas_region() + toml::walls() +
                                R"([[deposit]]
x = 0.0
y = 0.0
energy = 0.5
)";

class OptionTables : public ::testing::Test {
 protected:
  void SetUp() override { path_ = scratch_.write("scene.toml", small_scene); }

  stagger::Scene load(const std::string& key, const std::string& value) const {
    return stagger::load_scene(path_, {{key, value}});
  }
  std::string error_of(const std::string& key, const std::string& value) const {
    try {
      load(key, value);
    } catch (const stagger::Error& error) {
      return error.what();
    }
    return "(no error)";
  }

  const stagger::testing::ScratchDirectory scratch_{"option_table_test_" +
                                                    std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                                    "_" + stagger::testing::current_test_name()};
  std::string path_;
};

std::string toml_text(double value, stagger::OptionType type) {
  std::ostringstream out;
  if (type == stagger::OptionType::integer)
    out << static_cast<long long>(value);
  else {
    out.precision(17);
    out << value;
    if (out.str().find_first_of(".e") == std::string::npos) out << ".0";
  }
  return out.str();
}

// An admissible value other than the default.
template <class Options>
double other_value(const stagger::Option<Options>& option, double current) {
  if (option.type == stagger::OptionType::flag) return current != 0 ? 0.0 : 1.0;
  if (option.type == stagger::OptionType::choice) return current == 0 ? 1.0 : 0.0;
  // dt_min: a floor above the first CFL step is refused at load (the step would collapse),
  // so try a small floor first.
  const double small = std::string(option.key) == "dt_min" ? 1e-9 : current + 1;
  for (double candidate :
       {small, current + 1, current * 0.5, current - 1, 0.5 * (option.range.low + option.range.high)}) {
    if (option.type == stagger::OptionType::integer) candidate = std::round(candidate);
    if (candidate != current && option.check(candidate).empty()) return candidate;
  }
  ADD_FAILURE() << option.key << ": no admissible value other than " << current;
  return current;
}

std::string scene_text(const stagger::OptionType type, const std::string& written,
                       const std::vector<const char*>& names, double value) {
  if (type == stagger::OptionType::flag) return value != 0 ? "true" : "false";
  if (type == stagger::OptionType::choice) return std::string("\"") + names[static_cast<std::size_t>(value)] + "\"";
  return written;
}

}  // namespace

TEST(OptionTableDocs, ScenesMdHoldsTheGeneratedTables) {
  const fs::path path = fs::path(STAGGER_SOURCE_DIR) / "docs" / "scenes.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::ostringstream text;
  text << in.rdbuf();
  const std::string document = text.str();
  const std::string generated = stagger::with_generated_option_tables(document);
  EXPECT_TRUE(generated == document) << "docs/scenes.md's option tables differ from the code: run "
                                        "build/bin/stagger-options --update docs/scenes.md";
  // The default in the docs is the struct's: cfl 0.15 and max_retries 3 must appear as such.
  EXPECT_NE(document.find("| `cfl` | number | `0.15` | (0, 1) |"), std::string::npos);
  EXPECT_NE(document.find("| `max_retries` | integer | `3` | [0, 30] |"), std::string::npos);
}

TEST(OptionTableDocs, AChangedOrMissingBlockIsDetected) {
  const std::string document =
      "<!-- begin generated: time options -->\nstale\n<!-- end generated: time options -->\n"
      "<!-- begin generated: numerics options -->\n<!-- end generated: numerics options -->\n"
      "<!-- begin generated: output options -->\n<!-- end generated: output options -->\n"
      "<!-- begin generated: deposit options -->\n<!-- end generated: deposit options -->\n"
      "<!-- begin generated: material.strength options -->\n<!-- end generated: material.strength options -->\n"
      "<!-- begin generated: ideal_gas options -->\n<!-- end generated: ideal_gas options -->\n"
      "<!-- begin generated: mie_gruneisen options -->\n<!-- end generated: mie_gruneisen options -->\n"
      "<!-- begin generated: jwl options -->\n<!-- end generated: jwl options -->\n"
      "<!-- begin generated: stiffened_gas options -->\n<!-- end generated: stiffened_gas options -->\n"
      "<!-- begin generated: ale options -->\n<!-- end generated: ale options -->\n";
  const std::string generated = stagger::with_generated_option_tables(document);
  EXPECT_EQ(generated.find("stale"), std::string::npos);
  EXPECT_NE(generated.find("| `end` | number | required | > 0 | time |"), std::string::npos);
  EXPECT_EQ(stagger::with_generated_option_tables(generated), generated);
  EXPECT_THROW(stagger::with_generated_option_tables("<!-- begin generated: time options -->\n"), stagger::Error);
  EXPECT_THROW(stagger::with_generated_option_tables("text\n"), stagger::Error);
  EXPECT_THROW(stagger::with_generated_option_tables(
                   "<!-- begin generated: solver options -->\n<!-- end generated: solver options -->\n"),
               stagger::Error);
}

TEST(OptionTableRows, DefaultsAreAdmissibleAndKeysUnique) {
  auto check = [](const auto& table) {
    std::set<std::string> keys;
    for (const auto& option : table.options) {
      EXPECT_TRUE(keys.insert(option.key).second) << table.section << "." << option.key << " twice";
      EXPECT_NE(std::string(option.doc), "") << option.key;
      if (!option.required) {
        EXPECT_EQ(option.check(option.default_value()), "") << table.section << "." << option.key;
      }
    }
  };
  check(stagger::numerics_option_table());
  check(stagger::output_option_table());
  check(stagger::time_option_table());
  check(stagger::deposit_option_table());
  check(stagger::strength_option_table());
  check(stagger::ideal_gas_option_table());
  check(stagger::mie_gruneisen_option_table());
  check(stagger::jwl_option_table());
  check(stagger::stiffened_gas_option_table());
  check(stagger::ale_option_table());
}

TEST(OptionTableRows, RangeTexts) {
  EXPECT_EQ((stagger::OptionRange{0, 1, true, true}.text()), "in (0, 1)");
  EXPECT_EQ((stagger::OptionRange{0, 1, true, false}.text()), "in (0, 1]");
  EXPECT_EQ((stagger::OptionRange{1, INFINITY, false, true}.text()), ">= 1");
  EXPECT_EQ((stagger::OptionRange{0, INFINITY, true, true}.text()), "> 0");
  EXPECT_EQ(stagger::OptionRange{}.text(), "any finite value");
  EXPECT_FALSE(stagger::OptionRange{}.contains(NAN));
  EXPECT_FALSE(stagger::OptionRange{}.contains(INFINITY));
  EXPECT_TRUE((stagger::OptionRange{0, 1, false, false}.contains(1.0)));
  EXPECT_FALSE((stagger::OptionRange{0, 1, false, true}.contains(1.0)));
}

namespace {

// For every row of `table` (scene section `prefix`): a non-default admissible value set with
// --set lands in that row's member and in no other; values just outside each finite bound
// are rejected by the reader (naming the key) and by the library's validate().
template <class Options>
void check_table(const std::function<stagger::Scene(const std::string&, const std::string&)>& load,
                 const std::function<std::string(const std::string&, const std::string&)>& error_of,
                 const stagger::OptionTable<Options>& table, const std::string& prefix,
                 const std::function<const Options&(const stagger::Scene&)>& values_of,
                 const std::function<void(const stagger::Scene&, const Options&)>& validate) {
  const stagger::Scene base = load("time.end", "0.1");
  const Options& base_values = values_of(base);
  for (const auto& option : table.options) {
    SCOPED_TRACE(prefix + option.key);
    const double current = option.get(base_values);
    const double value = other_value(option, current);
    const stagger::Scene scene =
        load(prefix + option.key, scene_text(option.type, toml_text(value, option.type), option.choices, value));
    const Options& read = values_of(scene);
    EXPECT_EQ(option.get(read), value);
    for (const auto& other : table.options)
      if (&other != &option) {
        EXPECT_EQ(other.get(read), other.get(base_values)) << other.key << " moved";
      }

    if (option.type != stagger::OptionType::number && option.type != stagger::OptionType::integer) continue;
    std::vector<double> outside;
    const double step = option.type == stagger::OptionType::integer ? 1.0 : 1e-3;
    if (std::isfinite(option.range.low))
      outside.push_back(option.range.low_open ? option.range.low : option.range.low - step);
    if (std::isfinite(option.range.high))
      outside.push_back(option.range.high_open ? option.range.high : option.range.high + step);
    for (double bad : outside) {
      const std::string text = toml_text(bad, option.type);
      const std::string reader_error = error_of(prefix + option.key, text);
      EXPECT_NE(reader_error.find("key '" + prefix + option.key + "': must be"), std::string::npos) << reader_error;
      Options values = base_values;
      option.set(values, bad);
      try {
        validate(base, values);
        ADD_FAILURE() << "validate() accepted " << option.key << " = " << text;
      } catch (const stagger::Error& error) {
        EXPECT_NE(std::string(error.what()).find(std::string(option.key) + ": must be"), std::string::npos)
            << error.what();
      }
    }
  }
}

}  // namespace

TEST_F(OptionTables, ReaderAndValidateAgreeOnEveryRow) {
  const auto load_fn = [this](const std::string& key, const std::string& value) { return load(key, value); };
  const auto error_fn = [this](const std::string& key, const std::string& value) { return error_of(key, value); };
  check_table<stagger::HydroOptions>(
      load_fn, error_fn, stagger::numerics_option_table(), "numerics.",
      [](const stagger::Scene& s) -> const stagger::HydroOptions& { return s.problem.options; },
      [](const stagger::Scene&, const stagger::HydroOptions& values) {
        stagger::numerics_option_table().validate(values);
      });
  check_table<stagger::RunControl>(
      load_fn, error_fn, stagger::output_option_table(), "output.",
      [](const stagger::Scene& s) -> const stagger::RunControl& { return s.control; },
      [](const stagger::Scene&, const stagger::RunControl& values) { values.validate(); });
  check_table<stagger::EnergyDeposit>(
      load_fn, error_fn, stagger::deposit_option_table(), "deposit[0].",
      [](const stagger::Scene& s) -> const stagger::EnergyDeposit& { return s.problem.deposits.at(0); },
      [](const stagger::Scene&, const stagger::EnergyDeposit& values) {
        stagger::deposit_option_table().validate(values);
      });
  check_table<stagger::Strength>(
      load_fn, error_fn, stagger::strength_option_table(), "material[0].strength.",
      [](const stagger::Scene& s) -> const stagger::Strength& {
        return std::get<stagger::Strength>(*s.problem.materials.at(0).strength);
      },
      [](const stagger::Scene&, const stagger::Strength& values) {
        stagger::strength_option_table().validate(values);
      });
  check_table<stagger::IdealGas>(
      load_fn, error_fn, stagger::ideal_gas_option_table(), "material[0].",
      [](const stagger::Scene& s) -> const stagger::IdealGas& {
        return std::get<stagger::IdealGas>(s.problem.materials.at(0).eos);
      },
      [](const stagger::Scene&, const stagger::IdealGas& values) {
        stagger::ideal_gas_option_table().validate(values);
      });
  check_table<stagger::MieGruneisen>(
      load_fn, error_fn, stagger::mie_gruneisen_option_table(), "material[1].",
      [](const stagger::Scene& s) -> const stagger::MieGruneisen& {
        return std::get<stagger::MieGruneisen>(s.problem.materials.at(1).eos);
      },
      [](const stagger::Scene&, const stagger::MieGruneisen& values) {
        stagger::mie_gruneisen_option_table().validate(values);
      });
  check_table<stagger::Jwl>(
      load_fn, error_fn, stagger::jwl_option_table(), "material[2].",
      [](const stagger::Scene& s) -> const stagger::Jwl& {
        return std::get<stagger::Jwl>(s.problem.materials.at(2).eos);
      },
      [](const stagger::Scene&, const stagger::Jwl& values) { stagger::jwl_option_table().validate(values); });
}

// The library checks the same ranges on a Problem built in code (no scene involved).
TEST_F(OptionTables, ProblemValidateUsesTheTables) {
  const stagger::Scene scene = load("time.end", "0.1");
  auto rejects = [](const stagger::Problem& problem, const std::string& expected) {
    try {
      problem.validate();
      ADD_FAILURE() << "accepted; expected " << expected;
    } catch (const stagger::Error& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  };
  EXPECT_NO_THROW(scene.problem.validate());
  stagger::Problem problem = scene.problem;
  problem.options.max_retries = 31;
  rejects(problem, "numerics.max_retries: must be in [0, 30], got 31");
  problem.options.max_retries = 30;
  EXPECT_NO_THROW(problem.validate());
  problem.options.cfl = NAN;
  rejects(problem, "numerics.cfl: must be in (0, 1), got NaN");
  problem = scene.problem;
  problem.t_end = 0;
  rejects(problem, "time.end: must be > 0, got 0");
  problem = scene.problem;
  problem.deposits[0].energy = -1;
  rejects(problem, "deposit[0].energy: must be > 0, got -1");
  problem = scene.problem;
  std::get<stagger::LinearHardening>(*problem.materials[0].strength).yield_stress = 0;
  rejects(problem, "material 'gas': strength.yield_stress: must be > 0, got 0");
  problem = scene.problem;
  std::get<stagger::MieGruneisen>(problem.materials[1].eos).s = -0.5;
  rejects(problem, "material 'copper': s: must be >= 0, got -0.5");
  problem = scene.problem;
  problem.options.viscosity = static_cast<stagger::Viscosity>(7);
  rejects(problem, "numerics.viscosity: must be one of \"bulk\", \"edge\" or \"tensor\", got 7");

  stagger::RunControl control;
  EXPECT_NO_THROW(control.validate());
  control.history_every = 0;
  EXPECT_THROW(control.validate(), stagger::Error);
}

TEST_F(OptionTables, ReaderMessagesNameFileLineKeyAndMeaning) {
  EXPECT_NE(error_of("numerics.max_retries", "31")
                .find("key 'numerics.max_retries': must be in [0, 30], got 31; "
                      "halvings of dt"),
            std::string::npos)
      << error_of("numerics.max_retries", "31");
  EXPECT_NE(
      error_of("numerics.viscosity", "\"viscous\"").find("unknown value \"viscous\"; use one of \"bulk\", \"edge\""),
      std::string::npos);
  EXPECT_NE(error_of("output.history_every", "3000000000").find("must be at most 2147483647, got 3000000000"),
            std::string::npos)
      << error_of("output.history_every", "3000000000");
}

// [material.strength] picks its model by `model`; without the key it is the linear-hardening
// model, so scenes written before the key read unchanged.
TEST_F(OptionTables, StrengthModelKeyDefaultsToLinearHardening) {
  const stagger::Scene implicit = load("time.end", "0.1");
  const stagger::Scene named = load("material[0].strength.model", "\"linear_hardening\"");
  for (const stagger::Scene* scene : {&implicit, &named}) {
    ASSERT_TRUE(scene->problem.materials[0].strength);
    const auto* model = std::get_if<stagger::LinearHardening>(&*scene->problem.materials[0].strength);
    ASSERT_NE(model, nullptr);
    EXPECT_EQ(model->shear_modulus, 2.0);
    EXPECT_EQ(model->yield_stress, 3.0);
    EXPECT_EQ(model->hardening_modulus, 0.0);
  }
  const std::string unknown = error_of("material[0].strength.model", "\"johnson_cook\"");
  EXPECT_NE(unknown.find("unknown value \"johnson_cook\"; use one of \"linear_hardening\""), std::string::npos)
      << unknown;
}
